#pragma once
// Small file helpers shared by the writers.

#include <filesystem>
#include <functional>
#include <ostream>
#include <vector>

namespace dlslam::io {

// Writes a file atomically: `write` fills a temporary file beside `path`,
// which then replaces `path` in one rename. A failure (exception or stream
// error) leaves any existing file untouched and throws InputError.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

// The whole file as bytes (models, images handed to a decoder). Throws
// InputError naming the file when it is missing, a directory, unreadable or
// empty; `what` names the kind of file in the message ("model", ...).
std::vector<unsigned char> ReadFileBytes(const std::filesystem::path& path, const char* what);

}  // namespace dlslam::io
