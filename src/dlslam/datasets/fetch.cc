#include "dlslam/datasets/fetch.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>
#include <vector>

#include "dlslam/datasets/digest.h"

namespace dlslam::datasets {
namespace {

namespace fs = std::filesystem;

// An exclusive flock on DIR/.<name>.lock, so two fetches of one sequence
// into one folder cannot write the same .part file.
class FetchLock {
 public:
  explicit FetchLock(const fs::path& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError(path, 0, "cannot create lock file: {}", std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw Error(fmt::format("another fetch into the same folder holds {}", path.string()));
    }
  }
  ~FetchLock() {
    std::error_code ignored;
    fs::remove(path_, ignored);
    ::close(fd_);
  }
  FetchLock(const FetchLock&) = delete;
  FetchLock& operator=(const FetchLock&) = delete;

 private:
  fs::path path_;
  int fd_ = -1;
};

void RemoveQuietly(const fs::path& path) {
  std::error_code ignored;
  fs::remove_all(path, ignored);
}

// Throws (after removing the archive) when a known checksum does not match.
void VerifyChecksum(const fs::path& archive, DigestKind kind, const std::string& expected,
                    const std::string& actual) {
  if (expected.empty() || expected == actual) return;
  RemoveQuietly(archive);
  throw Error(fmt::format("{}: {} mismatch: expected {}, got {}; removed the download (rerun to fetch it again)",
                          archive.string(), DigestName(kind), expected, actual));
}

// The folder to move into place: the archive's single top folder, else the staging folder itself.
fs::path SequenceRoot(const fs::path& staging, const fs::path& archive) {
  const std::vector<fs::directory_entry> entries{fs::directory_iterator(staging), fs::directory_iterator()};
  if (entries.empty()) throw ArchiveContentError(archive, 0, "the archive is empty");
  if (entries.size() == 1 && entries[0].is_directory() && !entries[0].is_symlink()) return entries[0].path();
  return staging;
}

void WriteStamp(const fs::path& root, const std::string& url, const std::string& sha256) {
  std::ofstream out(root / kFetchStampName);
  out << "# written by `dlslam dataset fetch` after a complete, verified unpack\nurl " << url
      << "\nsha256 " << sha256 << "\n";
  if (!out.flush()) throw InputError(root / kFetchStampName, 0, "cannot write");
}

}  // namespace

void FetchOptions::Check() const {
  DLSLAM_CHECK(!dir.empty(), "the target folder must be given");
  if (!sha256.empty()) NormalizeHexDigest(sha256, DigestKind::kSha256, "--sha256");
  if (!md5.empty()) NormalizeHexDigest(md5, DigestKind::kMd5, "--md5");
  DLSLAM_CHECK(base_url.empty() || base_url.starts_with("http://") || base_url.starts_with("https://"),
               "base URL must start with http:// or https://, got '{}'", base_url);
  download.Check();
}

bool LooksLikeCompleteSequence(const fs::path& dir) {
  return fs::is_regular_file(dir / kFetchStampName) ||
         (fs::is_regular_file(dir / "rgb.txt") && fs::is_regular_file(dir / "depth.txt"));
}

FetchResult FetchSequence(const SequenceInfo& info, const FetchOptions& options) {
  options.Check();
  FetchResult result;
  result.sequence_dir = options.dir / info.name;
  const auto present = [&] {
    if (!fs::exists(result.sequence_dir)) return false;
    if (fs::is_directory(result.sequence_dir) && LooksLikeCompleteSequence(result.sequence_dir)) return true;
    throw InputError(result.sequence_dir, 0,
                     "exists but does not look like a complete sequence (no {}, no rgb.txt + depth.txt); "
                     "move it away or remove it, then rerun", kFetchStampName);
  };
  if (present()) {
    result.already_present = true;
    return result;
  }
  fs::create_directories(options.dir);
  const FetchLock lock(options.dir / ("." + info.name + ".lock"));
  if (present()) {  // another process may have finished it before we took the lock
    result.already_present = true;
    return result;
  }

  const std::string url = ArchiveUrl(info, options.base_url);
  const fs::path archive = options.dir / ArchiveFileName(info);
  const std::string expected_sha256 =
      options.sha256.empty() ? info.sha256 : NormalizeHexDigest(options.sha256, DigestKind::kSha256, "--sha256");
  const std::string expected_md5 =
      options.md5.empty() ? info.md5 : NormalizeHexDigest(options.md5, DigestKind::kMd5, "--md5");

  if (fs::is_regular_file(archive)) {  // complete download of an earlier run (size checked then)
    result.sha256 = FileDigestHex(archive, DigestKind::kSha256);
    const bool ok = (expected_sha256.empty() || expected_sha256 == result.sha256) &&
                    (expected_md5.empty() || expected_md5 == FileDigestHex(archive, DigestKind::kMd5));
    if (ok) {
      spdlog::info("using the archive of an earlier run: {}", archive.string());
      result.reused_archive = true;
    } else {
      spdlog::warn("{} does not match the expected checksum; downloading it again", archive.string());
      RemoveQuietly(archive);
    }
  }
  if (!result.reused_archive) {
    fs::path part = archive;
    part += ".part";
    DownloadOptions download = options.download;
    if (download.expected_size == 0) download.expected_size = info.size_bytes;
    spdlog::info("downloading {}", url);
    result.download = DownloadToFile(url, part, download);
    if (!result.download.size_verified) {
      spdlog::warn("{}: the server did not state the size; it could not be checked", url);
    }
    result.sha256 = FileDigestHex(part, DigestKind::kSha256);
    VerifyChecksum(part, DigestKind::kSha256, expected_sha256, result.sha256);
    if (!expected_md5.empty()) {
      VerifyChecksum(part, DigestKind::kMd5, expected_md5, FileDigestHex(part, DigestKind::kMd5));
    }
    fs::rename(part, archive);
  }
  spdlog::info("sha256 {}  {}", result.sha256, archive.filename().string());

  const fs::path staging = options.dir / ("." + info.name + ".staging");
  RemoveQuietly(staging);  // left over from an interrupted run
  fs::create_directory(staging);
  try {
    spdlog::info("unpacking {}", archive.string());
    result.extracted = ExtractArchive(archive, staging);
    const fs::path root = SequenceRoot(staging, archive);
    WriteStamp(root, url, result.sha256);
    fs::rename(root, result.sequence_dir);
  } catch (const ArchiveContentError& e) {
    RemoveQuietly(staging);
    if (!options.keep_archive) RemoveQuietly(archive);
    throw Error(fmt::format("{}{}", e.what(), options.keep_archive ? "" : "; removed the archive"));
  } catch (...) {
    RemoveQuietly(staging);  // keep the archive: the failure was on our side (disk, permissions)
    throw;
  }
  RemoveQuietly(staging);
  if (!options.keep_archive) RemoveQuietly(archive);
  return result;
}

}  // namespace dlslam::datasets
