// `dlslam composite` as a user runs it: real photos of people walked through
// a real static recording (7-Scenes frames and the CCP person photos of
// ../shared/data; skipped without them), and clear refusals.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "dlslam/io/sequence.h"
#include "tests/support/cli_run.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

testing::CliRun Cli(const std::string& args) {
  return testing::RunShell(testing::Quoted(DLSLAM_CLI_PATH) + " composite " + args + " 2>&1");
}

TEST(CompositeCliTest, WritesASequenceWithPersonMasksThatReadsBack) {
  DLSLAM_REQUIRE_SHARED_DATA(background, "7scenes-redkitchen-500");
  DLSLAM_REQUIRE_SHARED_DATA(people, "segmentation/ccp-person");
  const fs::path out = testing::MakeTempDir("composite") / "kitchen";
  // Close people so that the first frames see them.
  const testing::CliRun run = Cli("--background " + testing::Quoted(background) + " --people " +
                                  testing::Quoted(people) + " --out " + testing::Quoted(out) +
                                  " --frames 12 --count 3 --min-distance 1.0 --max-distance 1.2");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("wrote 12 frames"));
  const io::RgbdSequence written = io::RgbdSequence::Open(out);
  ASSERT_EQ(written.size(), 12u);
  ASSERT_TRUE(written.ground_truth().has_value());
  int with_people = 0;
  for (std::size_t i = 0; i < written.size(); ++i) {
    const io::RgbdFrame f = written.LoadFrame(i);
    ASSERT_FALSE(f.mask.empty());
    with_people += cv::countNonZero(f.mask) > 0;
  }
  EXPECT_GT(with_people, 0);
  fs::remove_all(out.parent_path());
}

TEST(CompositeCliTest, RefusesABackgroundWithoutPosesAndAMissingPeopleFolder) {
  DLSLAM_REQUIRE_SHARED_DATA(people, "segmentation/ccp-person");
  const fs::path root = testing::MakeTempDir("composite_bad");
  fs::create_directories(root / "seq" / "rgb");
  const testing::CliRun no_sequence =
      Cli("--background " + testing::Quoted(root / "seq") + " --people " + testing::Quoted(people) + " --out " +
          testing::Quoted(root / "out"));
  EXPECT_EQ(no_sequence.exit_code, 1) << no_sequence.output;
  EXPECT_THAT(no_sequence.output, HasSubstr("[error]"));
  DLSLAM_REQUIRE_SHARED_DATA(background, "7scenes-redkitchen-500");
  const testing::CliRun no_people = Cli("--background " + testing::Quoted(background) + " --people " +
                                        testing::Quoted(root) + " --out " + testing::Quoted(root / "out2"));
  EXPECT_EQ(no_people.exit_code, 1) << no_people.output;
  EXPECT_THAT(no_people.output, HasSubstr("images/"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace dlslam
