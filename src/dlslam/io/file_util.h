#pragma once
// Small file helpers shared by the writers.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace dlslam::io {

// Writes a file atomically: `write` fills a temporary file beside `path`,
// which then replaces `path` in one rename. A failure (exception or stream
// error) leaves any existing file untouched and throws InputError.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

// Size of `path` after checking that it can be read as a file: InputError
// (line 0) when it is missing, a folder, a device, FIFO or socket (read
// without end), a symlink loop or an unusable name, or over `max_bytes`.
// `what` names the kind of file in the message, with its article ("a
// settings file", "an image").
std::uintmax_t CheckReadableFile(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                 std::string_view what = "a file");

// The whole file in one read, after CheckReadableFile(path, max_bytes, what).
std::string ReadFileBytes(const std::filesystem::path& path, std::uintmax_t max_bytes = 1ull << 30,
                          std::string_view what = "a file");

// Regular files under `root` (recursively, following no symlinked folders)
// whose extension is one of `extensions` (with the dot, compared without
// case: ".png" matches "a.PNG"), sorted by path so that the order does not
// depend on the file system. Throws InputError when `root` is not a folder.
std::vector<std::filesystem::path> FindFilesRecursively(const std::filesystem::path& root,
                                                        const std::vector<std::string_view>& extensions);

}  // namespace dlslam::io
