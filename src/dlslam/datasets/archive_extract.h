#pragma once
// Safe unpacking of .tgz / .tar / .zip archives with libarchive.
//
// Every entry must stay inside the target folder: absolute paths, ".."
// components, symlinks whose target leaves the folder, hard links to outside,
// and device / fifo entries are refused, and nothing is ever written through
// a symlink. Unpack into a fresh staging folder: on an error the folder holds
// a partial tree that the caller throws away.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "dlslam/util/check.h"

namespace dlslam::datasets {

// The archive itself is bad (corrupt, truncated, not an archive, or holds an
// unsafe entry): downloading it again from the same place will not help
// unless it changed. Write-side failures (disk full) throw plain InputError.
class ArchiveContentError : public InputError {
 public:
  using InputError::InputError;
};

struct ExtractStats {
  std::size_t files = 0;        // regular files (hard links included)
  std::size_t directories = 0;  // directory entries
  std::size_t symlinks = 0;     // symbolic links (all pointing inside)
  std::uint64_t bytes = 0;      // bytes of file data written
};

// Unpacks `archive` into the existing folder `dest_dir`.
ExtractStats ExtractArchive(const std::filesystem::path& archive, const std::filesystem::path& dest_dir);

// The entry path made relative and checked: "./a/b" -> "a/b"; "" for the
// root entry "./". Throws ArchiveContentError for absolute paths and "..".
std::filesystem::path SafeEntryPath(const std::filesystem::path& archive, const std::string& entry_path);

}  // namespace dlslam::datasets
