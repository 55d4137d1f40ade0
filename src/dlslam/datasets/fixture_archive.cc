#include "dlslam/datasets/fixture_archive.h"

#include <archive.h>
#include <archive_entry.h>

#include <memory>
#include <stdexcept>

namespace dlslam::datasets::testing {
namespace {

la_ssize_t Append(struct archive*, void* user, const void* buffer, size_t length) {
  static_cast<std::string*>(user)->append(static_cast<const char*>(buffer), length);
  return static_cast<la_ssize_t>(length);
}

void Check(int r, struct archive* a) {
  if (r < ARCHIVE_WARN) throw std::runtime_error(std::string("fixture archive: ") + archive_error_string(a));
}

}  // namespace

std::string MakeArchive(const std::vector<FixtureEntry>& entries, ArchiveFormat format) {
  std::string out;
  std::unique_ptr<struct archive, int (*)(struct archive*)> a(archive_write_new(), archive_write_free);
  if (format == ArchiveFormat::kTgz) {
    Check(archive_write_set_format_pax_restricted(a.get()), a.get());
    Check(archive_write_add_filter_gzip(a.get()), a.get());
  } else {
    Check(archive_write_set_format_zip(a.get()), a.get());
  }
  // No zero padding after the compressed stream: truncating must cut real data.
  Check(archive_write_set_bytes_in_last_block(a.get(), 1), a.get());
  Check(archive_write_open2(a.get(), &out, nullptr, Append, nullptr, nullptr), a.get());
  for (const FixtureEntry& e : entries) {
    std::unique_ptr<struct archive_entry, void (*)(struct archive_entry*)> entry(archive_entry_new(),
                                                                                 archive_entry_free);
    archive_entry_set_pathname(entry.get(), e.path.c_str());
    archive_entry_set_mtime(entry.get(), 1341845688, 0);
    switch (e.type) {
      case FixtureEntry::Type::kFile:
        archive_entry_set_filetype(entry.get(), AE_IFREG);
        archive_entry_set_perm(entry.get(), 0644);
        archive_entry_set_size(entry.get(), static_cast<la_int64_t>(e.content.size()));
        break;
      case FixtureEntry::Type::kDirectory:
        archive_entry_set_filetype(entry.get(), AE_IFDIR);
        archive_entry_set_perm(entry.get(), 0755);
        break;
      case FixtureEntry::Type::kSymlink:
        archive_entry_set_filetype(entry.get(), AE_IFLNK);
        archive_entry_set_perm(entry.get(), 0777);
        archive_entry_set_symlink(entry.get(), e.content.c_str());
        break;
      case FixtureEntry::Type::kHardlink:
        archive_entry_set_filetype(entry.get(), AE_IFREG);
        archive_entry_set_perm(entry.get(), 0644);
        archive_entry_set_hardlink(entry.get(), e.content.c_str());
        break;
    }
    Check(archive_write_header(a.get(), entry.get()), a.get());
    if (e.type == FixtureEntry::Type::kFile && !e.content.empty()) {
      if (archive_write_data(a.get(), e.content.data(), e.content.size()) < 0) Check(ARCHIVE_FATAL, a.get());
    }
  }
  Check(archive_write_close(a.get()), a.get());
  return out;
}

std::vector<FixtureEntry> TinySequence(const std::string& name) {
  using Type = FixtureEntry::Type;
  // Not real PNGs: the fetch never decodes images, and the bytes only need to
  // survive the round trip (a PNG signature plus a marker naming the file).
  const std::string png = "\x89PNG\r\n\x1a\n";
  return {
      {name + "/", "", Type::kDirectory},
      {name + "/rgb.txt", "# color images\n1305031102.175304 rgb/1305031102.175304.png\n"
                          "1305031102.211214 rgb/1305031102.211214.png\n"},
      {name + "/depth.txt", "# depth maps\n1305031102.160407 depth/1305031102.160407.png\n"
                            "1305031102.194330 depth/1305031102.194330.png\n"},
      {name + "/groundtruth.txt", "# timestamp tx ty tz qx qy qz qw\n"
                                  "1305031102.1758 1.3405 0.6266 1.6575 0.6574 0.6126 -0.2949 -0.3248\n"},
      {name + "/rgb/", "", Type::kDirectory},
      {name + "/rgb/1305031102.175304.png", png + "rgb 1"},
      {name + "/rgb/1305031102.211214.png", png + "rgb 2"},
      {name + "/depth/", "", Type::kDirectory},
      {name + "/depth/1305031102.160407.png", png + "depth 1"},
      {name + "/depth/1305031102.194330.png", png + "depth 2"},
  };
}

}  // namespace dlslam::datasets::testing
