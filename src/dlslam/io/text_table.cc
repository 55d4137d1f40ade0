#include "dlslam/io/text_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "dlslam/util/check.h"

namespace dlslam::io {

TextTable ReadTextTable(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, 0, "file not found");
  if (std::filesystem::is_directory(path)) throw InputError(path, 0, "is a directory, expected a file");
  // A device or FIFO (/dev/zero) would be read without end.
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(path, 0, "not a regular file (a device, FIFO or socket)");
  }
  constexpr std::uintmax_t kMaxTextBytes = 1ull << 30;  // lists and trajectories are far smaller
  std::error_code ec;
  if (const std::uintmax_t size = std::filesystem::file_size(path, ec); !ec && size > kMaxTextBytes) {
    throw InputError(path, 0, "{} bytes, more than the {} MB a list or trajectory file may have", size,
                     kMaxTextBytes >> 20);
  }
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open for reading");
  TextTable table;
  table.path = path;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (text[first] == '#') {
      table.comments.push_back(text.substr(first + 1));
      continue;
    }
    for (char& c : text) {
      if (c == ',' || c == '\t') c = ' ';
    }
    std::istringstream fields(text);
    TextRow row;
    row.line = line;
    for (std::string f; fields >> f;) row.fields.push_back(std::move(f));
    table.rows.push_back(std::move(row));
  }
  if (in.bad()) throw InputError(path, line, "read error");
  return table;
}

double ParseDouble(std::string_view text, const std::filesystem::path& path, int line,
                   std::string_view what) {
  const std::string s(text);
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(value)) {
    throw InputError(path, line, "{} '{}' is not a finite number", what, s);
  }
  return value;
}

}  // namespace dlslam::io
