#pragma once
// Small file helpers shared by the writers.

#include <filesystem>
#include <functional>
#include <ostream>

namespace dlslam::io {

// Writes a file atomically: `write` fills a temporary file beside `path`,
// which then replaces `path` in one rename. A failure (exception or stream
// error) leaves any existing file untouched and throws InputError.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

}  // namespace dlslam::io
