#include "dlslam/io/file_util.h"

#include <fstream>
#include <iterator>
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

std::vector<unsigned char> ReadFileBytes(const std::filesystem::path& path, const char* what) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path, 0, "{} file not found", what);
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, 0, "{} file is a directory", what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open {} file for reading", what);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, 0, "read error in {} file", what);
  if (bytes.empty()) throw InputError(path, 0, "{} file is empty (0 bytes)", what);
  return bytes;
}

}  // namespace dlslam::io
