#include "dlslam/util/check.h"

namespace dlslam {

namespace {
std::string FileLinePrefix(const std::filesystem::path& file, int line) {
  return line > 0 ? fmt::format("{}:{}: ", file.string(), line) : fmt::format("{}: ", file.string());
}
}  // namespace

InputError::InputError(const std::filesystem::path& file, int line, const std::string& what)
    : Error(FileLinePrefix(file, line) + what), file_(file), line_(line) {}

namespace internal {

void ThrowCheckFailure(const char* file, int line, const char* condition, const std::string& values,
                       const std::string& message) {
  std::string text = fmt::format("check failed at {}:{}: {}", file, line, condition);
  if (!values.empty()) text += " " + values;
  if (!message.empty()) text += ": " + message;
  throw Error(text);
}

}  // namespace internal
}  // namespace dlslam
