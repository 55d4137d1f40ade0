#pragma once
// Where tests find data. Shared data (../shared/data, or $DLSLAM_SHARED_DATA)
// may be absent: a test that needs it calls DLSLAM_REQUIRE_SHARED_DATA, which
// skips with a message instead of passing silently.

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

namespace dlslam::testing {

// The project's source directory (tests/fixtures lives under it).
std::filesystem::path SourceDir();
// Fixture files committed with the tests: tests/fixtures/<relative>.
std::filesystem::path FixturePath(const std::string& relative);
// $DLSLAM_SHARED_DATA, else <source>/../shared/data, if it exists.
std::optional<std::filesystem::path> SharedDataDir();
// A fresh empty directory under the system temp dir; the test removes it.
std::filesystem::path MakeTempDir(const std::string& prefix);

}  // namespace dlslam::testing

#define DLSLAM_REQUIRE_SHARED_DATA(var, relative)                                         \
  const auto var##_root = ::dlslam::testing::SharedDataDir();                             \
  if (!var##_root || !std::filesystem::exists(*var##_root / (relative))) {                \
    GTEST_SKIP() << "shared data '" << (relative)                                         \
                 << "' not found (set DLSLAM_SHARED_DATA); skipping";                     \
  }                                                                                       \
  const std::filesystem::path var = *var##_root / (relative)
