#include "tests/support/test_data.h"

#include <atomic>
#include <cstdlib>
#include <random>
#include <string>

namespace dlslam::testing {

std::filesystem::path SourceDir() {
  if (const char* env = std::getenv("DLSLAM_SOURCE_DIR")) return env;
  return DLSLAM_SOURCE_DIR_DEFAULT;
}

std::filesystem::path FixturePath(const std::string& relative) {
  return SourceDir() / "tests" / "fixtures" / relative;
}

std::optional<std::filesystem::path> SharedDataDir() {
  std::filesystem::path dir;
  if (const char* env = std::getenv("DLSLAM_SHARED_DATA"); env && *env) {
    dir = env;
  } else {
    dir = SourceDir().parent_path() / "shared" / "data";
  }
  if (std::filesystem::is_directory(dir)) return dir;
  return std::nullopt;
}

std::filesystem::path MakeTempDir(const std::string& prefix) {
  static std::atomic<int> counter{0};
  std::random_device rd;
  const auto dir = std::filesystem::temp_directory_path() /
                   (prefix + "-" + std::to_string(rd()) + "-" + std::to_string(counter++));
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace dlslam::testing
