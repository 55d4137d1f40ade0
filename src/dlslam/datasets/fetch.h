#pragma once
// Fetching one catalogue sequence into a folder: download (resumable), verify,
// unpack into a hidden staging folder, and rename it into place.
//
//   FetchOptions options;
//   options.dir = "data";
//   FetchResult r = FetchSequence(FindSequence("fr3/walking_xyz"), options);
//   // r.sequence_dir == "data/rgbd_dataset_freiburg3_walking_xyz"
//
// Files in DIR while it runs: <archive>.part (the download so far, kept for a
// resume), <archive> (complete and verified), .<name>.staging/ (unpacking),
// .<name>.lock. DIR/<name> appears only when the sequence is complete.

#include <cstdint>
#include <filesystem>
#include <string>

#include "dlslam/datasets/archive_extract.h"
#include "dlslam/datasets/catalogue.h"
#include "dlslam/datasets/http_download.h"

namespace dlslam::datasets {

struct FetchOptions {
  std::filesystem::path dir;  // folder that receives DIR/<name>; created when missing
  std::string base_url;       // server prefix replacing the collection's default; "" = default
  std::string sha256;         // expected archive SHA-256 (hex); "" = the catalogue's, if it has one
  std::string md5;            // expected archive MD5 (hex); "" = the catalogue's, if it has one
  bool keep_archive = false;  // keep DIR/<archive> after a successful unpack (default: remove it)
  DownloadOptions download;   // timeouts, retries, progress bar

  // Throws dlslam::Error naming the bad field and its value.
  void Check() const;
};

struct FetchResult {
  std::filesystem::path sequence_dir;  // DIR/<name>
  bool already_present = false;        // nothing was done
  bool reused_archive = false;         // a complete archive from an earlier run was unpacked
  DownloadResult download;             // all zero when nothing was downloaded
  std::string sha256;                  // of the archive that was unpacked
  ExtractStats extracted;
};

// Name of the stamp file written into every sequence folder this tool unpacks.
inline constexpr const char* kFetchStampName = ".dlslam-fetch";

// True when `dir` holds our stamp, or (unpacked by other means) both rgb.txt and depth.txt.
bool LooksLikeCompleteSequence(const std::filesystem::path& dir);

// Throws dlslam::Error (DownloadError, ArchiveContentError, ...) naming the URL
// or file; on any error DIR/<name> is not created.
FetchResult FetchSequence(const SequenceInfo& info, const FetchOptions& options);

}  // namespace dlslam::datasets
