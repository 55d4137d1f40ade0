#include "dlslam/datasets/archive_extract.h"

#include <archive.h>
#include <archive_entry.h>
#include <spdlog/spdlog.h>

#include <memory>

namespace dlslam::datasets {
namespace {

namespace fs = std::filesystem;

struct ReadDeleter {
  void operator()(struct archive* a) const { archive_read_free(a); }
};
struct WriteDeleter {
  void operator()(struct archive* a) const { archive_write_free(a); }
};
using ArchivePtr = std::unique_ptr<struct archive, ReadDeleter>;
using DiskPtr = std::unique_ptr<struct archive, WriteDeleter>;

std::string Message(struct archive* a) {
  const char* text = archive_error_string(a);
  return text != nullptr ? text : "unknown libarchive error";
}

const char* EntryName(struct archive_entry* entry) {
  if (const char* name = archive_entry_pathname(entry)) return name;
  if (const char* name = archive_entry_pathname_utf8(entry)) return name;
  return nullptr;
}

}  // namespace

fs::path SafeEntryPath(const fs::path& archive, const std::string& entry_path) {
  if (entry_path.empty()) throw ArchiveContentError(archive, 0, "entry with an empty name");
  const fs::path path(entry_path);
  if (path.is_absolute() || entry_path.front() == '/' || entry_path.front() == '\\') {
    throw ArchiveContentError(archive, 0, "refusing entry '{}': absolute path", entry_path);
  }
  fs::path out;
  for (const fs::path& part : path) {
    if (part == "..") {
      throw ArchiveContentError(archive, 0, "refusing entry '{}': '..' leaves the target folder", entry_path);
    }
    if (part != "." && !part.empty()) out /= part;
  }
  return out;
}

ExtractStats ExtractArchive(const fs::path& archive, const fs::path& dest_dir) {
  // Canonical: SECURE_SYMLINKS must not trip over symlinks in the caller's own path.
  const fs::path dest = fs::canonical(dest_dir);
  ArchivePtr reader(archive_read_new());
  DiskPtr disk(archive_write_disk_new());
  if (!reader || !disk) throw Error("libarchive failed to initialise");
  archive_read_support_filter_all(reader.get());
  archive_read_support_format_tar(reader.get());
  archive_read_support_format_gnutar(reader.get());
  archive_read_support_format_zip(reader.get());
  // Our own checks come first (clear messages); these are the second line.
  archive_write_disk_set_options(disk.get(), ARCHIVE_EXTRACT_TIME | ARCHIVE_EXTRACT_SECURE_NODOTDOT |
                                                 ARCHIVE_EXTRACT_SECURE_SYMLINKS);
  if (archive_read_open_filename(reader.get(), archive.c_str(), 1 << 16) != ARCHIVE_OK) {
    throw ArchiveContentError(archive, 0, "corrupt or unreadable archive: {}", Message(reader.get()));
  }
  ExtractStats stats;
  for (;;) {
    struct archive_entry* entry = nullptr;
    int r = archive_read_next_header(reader.get(), &entry);
    if (r == ARCHIVE_EOF) break;
    if (r == ARCHIVE_WARN) spdlog::warn("{}: {}", archive.string(), Message(reader.get()));
    if (r < ARCHIVE_WARN) throw ArchiveContentError(archive, 0, "corrupt archive: {}", Message(reader.get()));
    const char* raw_name = EntryName(entry);
    if (raw_name == nullptr) throw ArchiveContentError(archive, 0, "entry without a readable name");
    const std::string name = raw_name;  // copied: the entry's own buffer is rewritten below
    const fs::path relative = SafeEntryPath(archive, name);
    if (relative.empty()) continue;  // "./": the target folder itself
    const auto type = archive_entry_filetype(entry);
    if (const char* hardlink = archive_entry_hardlink(entry)) {
      archive_entry_copy_hardlink(entry, (dest / SafeEntryPath(archive, hardlink)).c_str());
      ++stats.files;
    } else if (type == AE_IFLNK) {
      const char* target = archive_entry_symlink(entry);
      const fs::path resolved = (relative.parent_path() / (target ? target : "")).lexically_normal();
      if (target == nullptr || fs::path(target).is_absolute() || resolved.empty() ||
          *resolved.begin() == "..") {
        throw ArchiveContentError(archive, 0, "refusing symlink '{}' -> '{}': it points outside the target folder",
                                  name, target ? target : "");
      }
      ++stats.symlinks;
    } else if (type == AE_IFDIR) {
      ++stats.directories;
    } else if (type == AE_IFREG) {
      ++stats.files;
    } else {
      throw ArchiveContentError(archive, 0, "refusing entry '{}': not a file, folder or link", name);
    }
    archive_entry_copy_pathname(entry, (dest / relative).c_str());
    r = archive_write_header(disk.get(), entry);
    if (r < ARCHIVE_WARN) throw InputError(dest / relative, 0, "cannot create: {}", Message(disk.get()));
    if (r == ARCHIVE_WARN) spdlog::warn("{}: {}", (dest / relative).string(), Message(disk.get()));
    if (type == AE_IFREG && archive_entry_hardlink(entry) == nullptr) {
      for (;;) {
        const void* block = nullptr;
        size_t size = 0;
        la_int64_t offset = 0;
        r = archive_read_data_block(reader.get(), &block, &size, &offset);
        if (r == ARCHIVE_EOF) break;
        if (r < ARCHIVE_WARN) {
          throw ArchiveContentError(archive, 0, "corrupt archive at '{}': {}", name, Message(reader.get()));
        }
        if (archive_write_data_block(disk.get(), block, size, offset) < ARCHIVE_WARN) {
          throw InputError(dest / relative, 0, "cannot write: {}", Message(disk.get()));
        }
        stats.bytes += size;
      }
    }
    if (archive_write_finish_entry(disk.get()) < ARCHIVE_WARN) {
      throw InputError(dest / relative, 0, "cannot finish: {}", Message(disk.get()));
    }
  }
  if (archive_write_close(disk.get()) < ARCHIVE_WARN) {
    throw InputError(dest, 0, "cannot finish unpacking: {}", Message(disk.get()));
  }
  return stats;
}

}  // namespace dlslam::datasets
