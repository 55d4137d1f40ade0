#include "dlslam/util/check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>

namespace dlslam {
namespace {

using ::testing::HasSubstr;

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(Check, PassingChecksDoNothing) {
  EXPECT_NO_THROW(DLSLAM_CHECK(1 + 1 == 2));
  EXPECT_NO_THROW(DLSLAM_CHECK_EQ(3, 3, "never shown"));
  EXPECT_NO_THROW(DLSLAM_CHECK_LT(1.0, 2.0));
}

TEST(Check, FailureSaysTheMessageFirstThenConditionValuesAndPlace) {
  const int width = 320;
  const std::string m = MessageOf([&] { DLSLAM_CHECK_EQ(width, 640, "image {} is too narrow", "a.png"); });
  EXPECT_THAT(m, HasSubstr("check_test.cc:"));
  EXPECT_THAT(m, HasSubstr("width == 640"));
  EXPECT_THAT(m, HasSubstr("(320 vs. 640)"));
  EXPECT_THAT(m, ::testing::StartsWith("image a.png is too narrow (check width == 640"));
}

TEST(Check, PlainCheckWithoutMessage) {
  const std::string m = MessageOf([] { DLSLAM_CHECK(false); });
  EXPECT_THAT(m, HasSubstr("check failed"));
  EXPECT_THAT(m, HasSubstr("false"));
}

TEST(InputError, NamesFileAndLine) {
  const InputError e("/data/rgb.txt", 12, "expected {} fields, got {}", 2, 1);
  EXPECT_STREQ(e.what(), "/data/rgb.txt:12: expected 2 fields, got 1");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.file(), "/data/rgb.txt");
  const InputError whole("/data/depth.png", 0, "not 16-bit");
  EXPECT_STREQ(whole.what(), "/data/depth.png: not 16-bit");
}

}  // namespace
TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("abc", ""), 3u);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("tracker", "trackr"), 1u);
  EXPECT_EQ(EditDistance("walking_xyz", "walking_xyz"), 0u);
}

}  // namespace dlslam
