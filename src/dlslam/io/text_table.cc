#include "dlslam/io/text_table.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"

namespace dlslam::io {

TextTable ReadTextTable(const std::filesystem::path& path) {
  // Lists and trajectories are far smaller; a device or FIFO (/dev/zero)
  // would be read without end.
  CheckReadableFile(path, 1ull << 30, "a list or trajectory file");
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
    throw InputError(path, line, "{} {} is not a finite number", what, Quoted(s));
  }
  return value;
}

}  // namespace dlslam::io
