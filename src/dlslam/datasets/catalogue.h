#pragma once
// The public RGB-D sequences `dlslam dataset fetch` knows: every TUM RGB-D
// sequence (freiburg1/2/3, including the validation and calibration ones)
// and every Bonn RGB-D Dynamic sequence, with where their archives live.
//
//   const SequenceInfo& seq = FindSequence("fr3/walking_xyz");
//   ArchiveUrl(seq, "")   // https://cvg.cit.tum.de/rgbd/dataset/freiburg3/rgbd_dataset_freiburg3_walking_xyz.tgz

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dlslam::datasets {

enum class Collection { kTum, kBonn };

struct SequenceInfo {
  // Full name: the folder the archive unpacks to, e.g. "rgbd_dataset_freiburg3_walking_xyz".
  std::string name;
  Collection collection = Collection::kTum;
  // Grouping as on the publishers' download pages, e.g. "dynamic", "validation".
  std::string category;
  // Archive path relative to the collection's base URL, e.g. "freiburg3/....tgz".
  std::string archive_path;
  // Archive size in bytes; 0 = not known (then only the server's
  // Content-Length / Content-Range total is checked).
  std::uint64_t size_bytes = 0;
  // Lower-case hex digests of the archive; empty = not known.
  std::string sha256;
  std::string md5;
};

// Every known sequence (catalogue_data.cc), TUM first, in a fixed order.
const std::vector<SequenceInfo>& Catalogue();

// Default server prefix of a collection (no trailing slash).
std::string_view DefaultBaseUrl(Collection collection);
std::string_view CollectionName(Collection collection);  // "tum" / "bonn"

// Short name: "fr3/walking_xyz", "bonn/crowd".
std::string ShortName(const SequenceInfo& info);
// The archive's file name, e.g. "rgbd_bonn_crowd.zip".
std::string ArchiveFileName(const SequenceInfo& info);
// base_url (or the default when empty; a trailing '/' is allowed) + "/" + archive_path.
std::string ArchiveUrl(const SequenceInfo& info, std::string_view base_url);

// Accepts the full name and the short forms, case-insensitively:
//   rgbd_dataset_freiburg3_walking_xyz, freiburg3_walking_xyz, fr3/walking_xyz, fr3_walking_xyz,
//   rgbd_bonn_crowd, bonn/crowd, bonn_crowd.
// Returns nullptr when unknown.
const SequenceInfo* LookupSequence(std::string_view name);
// As LookupSequence, but an unknown name throws dlslam::Error listing close matches.
const SequenceInfo& FindSequence(std::string_view name);
// The whole catalogue as a JSON array (what `dlslam dataset list --json` prints):
// [{"name", "short_name", "collection", "category", "url", "size_bytes", "sha256", "md5"}]
// with null for unknown sizes and checksums.
std::string CatalogueJson();

// Up to max_count known short names closest to `name` (edit distance, substrings first).
std::vector<std::string> CloseMatches(std::string_view name, std::size_t max_count = 5);

}  // namespace dlslam::datasets
