#include "dlslam/datasets/progress_bar.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

namespace dlslam::datasets {
namespace {

using ::testing::HasSubstr;

TEST(ProgressBar, FormatsFractionSizesAndSpeed) {
  constexpr std::uint64_t kMiB = 1 << 20;
  const std::string half = ProgressBar::Format(50 * kMiB, 100 * kMiB, 2.0 * kMiB);
  EXPECT_THAT(half, HasSubstr(" 50.0%"));
  EXPECT_THAT(half, HasSubstr("50.0 / 100.0 MiB"));
  EXPECT_THAT(half, HasSubstr("2.0 MiB/s"));
  EXPECT_EQ(std::count(half.begin(), half.end(), '#'), 12);  // half of the 24-wide bar
  EXPECT_EQ(std::count(half.begin(), half.end(), '.'), 12 + 4);  // bar + decimals
  // Unknown total: just the amount; over-full clamps at 100 %.
  EXPECT_THAT(ProgressBar::Format(3 * kMiB, 0, 0), HasSubstr("3.0 MiB"));
  EXPECT_THAT(ProgressBar::Format(3 * kMiB, 0, 0), ::testing::Not(HasSubstr("%")));
  EXPECT_THAT(ProgressBar::Format(200, 100, 0), HasSubstr("100.0%"));
}

TEST(ProgressBar, CountsItemsInTheirUnit) {
  const std::string bar = ProgressBar::Format(400, 800, 14.2, "frames");
  EXPECT_THAT(bar, HasSubstr(" 50.0%"));
  EXPECT_THAT(bar, HasSubstr("400 / 800 frames"));
  EXPECT_THAT(bar, HasSubstr("14.2 frames/s"));
  EXPECT_THAT(bar, ::testing::Not(HasSubstr("MiB")));
  EXPECT_THAT(ProgressBar::Format(7, 0, 0, "frames"), HasSubstr("7 frames"));
}

TEST(ProgressBar, DrawsNothingWhenDisabled) {
  ::testing::internal::CaptureStderr();
  {
    ProgressBar bar("x", false);
    bar.Update(1, 2);
    bar.Finish();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace dlslam::datasets
