#pragma once
// Test-only: builds small .tgz / .zip archives in memory with libarchive,
// including the malformed and malicious ones a server could send.

#include <string>
#include <vector>

namespace dlslam::datasets::testing {

struct FixtureEntry {
  enum class Type { kFile, kDirectory, kSymlink, kHardlink };
  std::string path;     // stored as-is (may be absolute or hold ".." on purpose)
  std::string content;  // file bytes, or the link target for links
  Type type = Type::kFile;
};

enum class ArchiveFormat { kTgz, kZip };

std::string MakeArchive(const std::vector<FixtureEntry>& entries, ArchiveFormat format);

// A tiny TUM-layout sequence under top folder `name`: rgb.txt, depth.txt,
// groundtruth.txt, rgb/ and depth/ with two placeholder PNG files each.
std::vector<FixtureEntry> TinySequence(const std::string& name);

}  // namespace dlslam::datasets::testing
