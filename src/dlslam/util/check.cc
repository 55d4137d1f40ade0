#include "dlslam/util/check.h"

#include <algorithm>
#include <string_view>
#include <vector>

namespace dlslam {

std::string ShortPath(const std::filesystem::path& file) {
  constexpr std::size_t kKeep = 100;
  const std::string name = file.string();
  if (name.size() <= 2 * kKeep + 20) return name;
  return fmt::format("{}...({} characters)...{}", name.substr(0, kKeep), name.size(),
                     name.substr(name.size() - kKeep));
}

namespace {

std::string FileLinePrefix(const std::filesystem::path& file, int line) {
  return line > 0 ? fmt::format("{}:{}: ", ShortPath(file), line) : fmt::format("{}: ", ShortPath(file));
}

}  // namespace

std::string Quoted(std::string_view text, std::size_t max_chars) {
  if (text.size() <= max_chars) return fmt::format("'{}'", text);
  return fmt::format("'{}...' ({} characters)", text.substr(0, max_chars), text.size());
}

InputError::InputError(const std::filesystem::path& file, int line, const std::string& what)
    : Error(FileLinePrefix(file, line) + what), file_(file), line_(line), problem_(what) {}

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

namespace internal {

void ThrowCheckFailure(const char* file, int line, const char* condition, const std::string& values,
                       const std::string& message) {
  // What is wrong first, in the words of the message; where the check sits
  // after it, relative to the source tree (not the build machine's path).
  std::string_view where = file;
  if (const auto src = where.rfind("src/"); src != std::string_view::npos) where.remove_prefix(src);
  std::string check = fmt::format("{}{}{} at {}:{}", condition, values.empty() ? "" : " ", values, where, line);
  if (message.empty()) throw Error("internal check failed: " + check);
  throw Error(fmt::format("{} (check {})", message, check));
}

}  // namespace internal
}  // namespace dlslam
