#pragma once
// Errors and checks. Every failure names where it happened and the values
// involved; nothing calls exit() or abort() on bad input.
//
//   DLSLAM_CHECK(depth_factor > 0, "depth factor must be positive");
//   DLSLAM_CHECK_EQ(image.cols, camera.width, "image {} has the wrong width", path);
//   throw InputError(path, line, "expected 8 numbers, got {}", n);

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace dlslam {

// Base of every error the library throws. The CLI turns it into a message and
// a non-zero exit.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad user input: a file that is missing, malformed or inconsistent. The
// message starts with "file:line: " (line 0 = the file as a whole).
class InputError : public Error {
 public:
  InputError(const std::filesystem::path& file, int line, const std::string& what);
  template <typename... Args>
  InputError(const std::filesystem::path& file, int line, fmt::format_string<Args...> format,
             Args&&... args)
      : InputError(file, line, fmt::format(format, std::forward<Args>(args)...)) {}

  const std::filesystem::path& file() const { return file_; }
  int line() const { return line_; }
  // What is wrong, without the "file:line: " in front.
  const std::string& problem() const { return problem_; }

 private:
  std::filesystem::path file_;
  int line_;
  std::string problem_;
};

// A path as named in a message: one longer than ~220 characters is cut in
// the middle, with its length.
std::string ShortPath(const std::filesystem::path& file);

// `text` in single quotes, cut to `max_chars` with its length: a message may
// echo a user's token, and a 100 KB token must not become a 100 KB line.
std::string Quoted(std::string_view text, std::size_t max_chars = 60);

// Levenshtein distance (insertions, deletions, substitutions), for the
// "did you mean" of an unknown name.
std::size_t EditDistance(std::string_view a, std::string_view b);

namespace internal {

inline std::string FormatMessage() { return {}; }
template <typename... Args>
std::string FormatMessage(fmt::format_string<Args...> format, Args&&... args) {
  return fmt::format(format, std::forward<Args>(args)...);
}

[[noreturn]] void ThrowCheckFailure(const char* file, int line, const char* condition,
                                    const std::string& values, const std::string& message);

template <typename A, typename B>
std::string FormatValues(const A& a, const B& b) {
  return fmt::format("({} vs. {})", a, b);
}

}  // namespace internal
}  // namespace dlslam

#define DLSLAM_CHECK(condition, ...)                                                     \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      ::dlslam::internal::ThrowCheckFailure(__FILE__, __LINE__, #condition, "",          \
                                            ::dlslam::internal::FormatMessage(__VA_ARGS__)); \
    }                                                                                    \
  } while (false)

#define DLSLAM_CHECK_OP_(a, op, b, ...)                                                  \
  do {                                                                                   \
    const auto& dlslam_check_a_ = (a);                                                   \
    const auto& dlslam_check_b_ = (b);                                                   \
    if (!(dlslam_check_a_ op dlslam_check_b_)) {                                         \
      ::dlslam::internal::ThrowCheckFailure(                                             \
          __FILE__, __LINE__, #a " " #op " " #b,                                         \
          ::dlslam::internal::FormatValues(dlslam_check_a_, dlslam_check_b_),            \
          ::dlslam::internal::FormatMessage(__VA_ARGS__));                               \
    }                                                                                    \
  } while (false)

#define DLSLAM_CHECK_EQ(a, b, ...) DLSLAM_CHECK_OP_(a, ==, b, __VA_ARGS__)
#define DLSLAM_CHECK_NE(a, b, ...) DLSLAM_CHECK_OP_(a, !=, b, __VA_ARGS__)
#define DLSLAM_CHECK_LT(a, b, ...) DLSLAM_CHECK_OP_(a, <, b, __VA_ARGS__)
#define DLSLAM_CHECK_LE(a, b, ...) DLSLAM_CHECK_OP_(a, <=, b, __VA_ARGS__)
#define DLSLAM_CHECK_GT(a, b, ...) DLSLAM_CHECK_OP_(a, >, b, __VA_ARGS__)
#define DLSLAM_CHECK_GE(a, b, ...) DLSLAM_CHECK_OP_(a, >=, b, __VA_ARGS__)
