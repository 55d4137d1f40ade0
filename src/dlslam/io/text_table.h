#pragma once
// Whitespace-separated text files of the TUM layout (rgb.txt, depth.txt,
// groundtruth.txt, associations, trajectories): '#' starts a comment line,
// blank lines are skipped, commas and tabs count as spaces (as in the TUM
// tools). Every row remembers its line number for error messages.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dlslam::io {

struct TextRow {
  int line = 0;  // 1-based line number in the file
  std::vector<std::string> fields;
};

struct TextTable {
  std::filesystem::path path;
  std::vector<std::string> comments;  // comment lines without the leading '#'
  std::vector<TextRow> rows;
};

// Throws InputError if the file is missing or unreadable.
TextTable ReadTextTable(const std::filesystem::path& path);

// Parses a finite double; throws InputError("path:line: <what> '<text>' is not a number").
double ParseDouble(std::string_view text, const std::filesystem::path& path, int line,
                   std::string_view what);

}  // namespace dlslam::io
