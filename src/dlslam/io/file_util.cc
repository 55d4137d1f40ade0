#include "dlslam/io/file_util.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <system_error>

#include "dlslam/util/check.h"

namespace dlslam::io {

void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path parent = path.has_parent_path() ? path.parent_path() : ".";
  if (!std::filesystem::is_directory(parent)) {
    throw InputError(path, 0, "cannot write: directory '{}' does not exist", parent.string());
  }
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    if (!out) throw InputError(path, 0, "cannot open '{}' for writing", tmp.string());
    try {
      write(out);
    } catch (...) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw InputError(path, 0, "write failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path, 0, "cannot replace file: {}", ec.message());
  }
}

std::uintmax_t CheckReadableFile(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                 std::string_view what) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) {
    throw InputError(path, 0, "cannot read it: {}", ec.message());  // ELOOP, ENAMETOOLONG
  }
  if (!std::filesystem::exists(status)) throw InputError(path, 0, "file not found");
  if (std::filesystem::is_directory(status)) throw InputError(path, 0, "a folder, expected {}", what);
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(path, 0, "not a regular file (a device, FIFO or socket)");
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot read its size: {}", ec.message());
  if (size > max_bytes) {
    throw InputError(path, 0, "{} bytes, more than the {} {} may have", size,
                     max_bytes >= (1u << 20) ? fmt::format("{} MB", max_bytes >> 20)
                                             : fmt::format("{} KB", max_bytes >> 10),
                     what);
  }
  return size;
}

std::string ReadFileBytes(const std::filesystem::path& path, std::uintmax_t max_bytes, std::string_view what) {
  CheckReadableFile(path, max_bytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path, 0, "cannot determine the file size");
  if (static_cast<std::uintmax_t>(size) > max_bytes) throw InputError(path, 0, "grew while being read");
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), size);
  if (in.gcount() != size) {
    throw InputError(path, 0, "read {} of {} bytes", in.gcount(), size);
  }
  return bytes;
}

namespace {

std::string Lower(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower;
}

}  // namespace

std::vector<std::filesystem::path> FindFilesRecursively(const std::filesystem::path& root,
                                                        const std::vector<std::string_view>& extensions) {
  if (!std::filesystem::is_directory(root)) throw InputError(root, 0, "not a folder");
  std::vector<std::string> wanted;
  for (std::string_view extension : extensions) wanted.push_back(Lower(extension));
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(root, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file()) continue;
    const std::string extension = Lower(it->path().extension().string());
    if (std::find(wanted.begin(), wanted.end(), extension) != wanted.end()) files.push_back(it->path());
  }
  if (ec) throw InputError(root, 0, "cannot list the folder: {}", ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace dlslam::io
