#include "dlslam/system/dynamic_options.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dlslam/system/slam_system.h"
#include "dlslam/util/check.h"

namespace dlslam {
namespace {

using ::testing::HasSubstr;

std::string CheckError(const DynamicOptions& options) {
  try {
    options.Check();
  } catch (const Error& e) {
    return e.what();
  }
  return "<no error>";
}

TEST(DynamicOptions, ModeNamesRoundTrip) {
  for (DynamicMode mode : {DynamicMode::kOrb, DynamicMode::kSemantic, DynamicMode::kGeometry, DynamicMode::kFull}) {
    EXPECT_EQ(ParseDynamicMode(ToString(mode)), mode);
  }
  EXPECT_TRUE(UsesSemanticPrior(DynamicMode::kFull));
  EXPECT_FALSE(UsesSemanticPrior(DynamicMode::kGeometry));
  EXPECT_TRUE(UsesGeometry(DynamicMode::kGeometry));
  EXPECT_FALSE(UsesGeometry(DynamicMode::kSemantic));
  EXPECT_FALSE(UsesGeometry(DynamicMode::kOrb) || UsesSemanticPrior(DynamicMode::kOrb));
}

TEST(DynamicOptions, UnknownModeNamesTheChoices) {
  try {
    ParseDynamicMode("dyna");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown dynamic mode 'dyna' (choose orb, semantic, geometry or full)"));
  }
}

TEST(DynamicOptions, DefaultsAreValidAndTheBaseline) {
  const DynamicOptions options;
  EXPECT_NO_THROW(options.Check());
  EXPECT_EQ(options.mode, DynamicMode::kOrb);
  EXPECT_EQ(options.geometry.multiview.max_reference_views, 5);  // the paper's N
}

TEST(DynamicOptions, CheckNamesTheBadField) {
  DynamicOptions options;
  options.mode = static_cast<DynamicMode>(7);
  EXPECT_THAT(CheckError(options), HasSubstr("unknown dynamic mode 7"));
  options = DynamicOptions();
  options.geometry.multiview.max_reference_views = 0;
  EXPECT_THAT(CheckError(options), HasSubstr("max_reference_views"));
  options = DynamicOptions();
  options.fusion.dilation_px = -1;
  EXPECT_THAT(CheckError(options), HasSubstr("dilation_px"));
  // The system checks its dynamic part too.
  SystemOptions system;
  system.dynamic.geometry.ant.rho = 1.5;
  EXPECT_THROW(system.Check(), Error);
}

}  // namespace
}  // namespace dlslam
