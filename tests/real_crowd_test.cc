// The whole system on real sensor data: frames 280-579 of the Bonn RGB-D
// Dynamic "crowd" sequence (three people walking close to a handheld Xtion,
// motion-capture ground truth; ../shared/data/bonn). Run as a user runs it
// (`dlslam run ... --sequential`), judged by the report: frames posed per
// pose source, and ATE over every posed frame (an ATE over the frames that
// happen to be tracked would hide failures). Skipped when the shared data is
// absent. Bounds are set from measured runs with a margin for the chaotic
// nature of SLAM on real data (docs/real-data.md has the numbers).

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_run.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

namespace fs = std::filesystem;

const char* const kBonnCrowd = "bonn/rgbd_bonn_crowd_280-579";

struct Outcome {
  nlohmann::json report;
  std::string log;
};

// `how`: "--sequential", or the threads' options.
Outcome RunOn(const fs::path& sequence, const std::string& mode, const std::string& how = "--sequential") {
  const fs::path out = testing::MakeTempDir("real_crowd");
  const std::string command = testing::Quoted(DLSLAM_CLI_PATH) + " run --sequence " + testing::Quoted(sequence) +
                              " --mode " + mode + " " + how + " --out " + testing::Quoted(out / "traj.txt") +
                              " --report " + testing::Quoted(out / "report.json") + " 2>&1";
  const testing::CliRun run = testing::RunShell(command);
  Outcome outcome;
  outcome.log = run.output;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  std::ifstream in(out / "report.json");
  if (in) outcome.report = nlohmann::json::parse(in);
  // Every frame has a line in the pose-source file, frames without a pose too.
  std::ifstream sources(out / "traj.sources.txt");
  int lines = 0;
  for (std::string line; std::getline(sources, line);) lines += !line.empty() && line[0] != '#';
  EXPECT_EQ(lines, 300);
  fs::remove_all(out);
  return outcome;
}

double AteRmse(const nlohmann::json& report) { return report.at("ate").at("rmse").get<double>(); }

// Full mode (the network's people + geometry): every frame posed through the
// two crowded stretches where people cover most of the view (25 of 300 had
// no pose before features were re-extracted on the static regions), at
// DynaSLAM's published accuracy for the whole sequence (0.016 m).
TEST(RealCrowdTest, FullModePosesEveryFrameAccurately) {
  DLSLAM_REQUIRE_SHARED_DATA(sequence, kBonnCrowd);
  const Outcome run = RunOn(sequence, "full");
  ASSERT_TRUE(run.report.contains("ate")) << run.log;
  const nlohmann::json& r = run.report;
  RecordProperty("ate_mm", static_cast<int>(AteRmse(r) * 1000));
  EXPECT_EQ(r.at("frames").get<int>(), 300);
  EXPECT_GE(r.at("frames_posed").get<int>(), 299) << run.log;  // >= 99.5 %
  EXPECT_LE(r.at("pose_sources").at("coasted").get<int>(), 5);
  // People in most frames: geometry removes enough for a re-extraction on a
  // third of them (97 with keyframes at least every 10 frames and gated
  // keyframes, 128 before, when geometry flagged more still structure).
  EXPECT_GT(r.at("frames_reextracted").get<int>(), 75);
  EXPECT_LT(AteRmse(r), 0.022) << run.log;
  EXPECT_EQ(r.at("ate").at("pairs").get<int>(), r.at("frames_posed").get<int>());
  // Against the camera poses (the published marker poses transformed as the
  // dataset's tool does): the same ATE within a few mm, and an RPE that
  // means something (the marker's turns about another centre read as
  // 9-12 deg/s of error; the camera's 0.6 deg/s).
  EXPECT_EQ(r.at("ground_truth").get<std::string>(), "published");
  ASSERT_TRUE(r.contains("bonn_camera")) << run.log;
  const nlohmann::json& camera = r.at("bonn_camera");
  EXPECT_EQ(camera.at("ground_truth").get<std::string>(), "bonn-camera");
  EXPECT_NEAR(AteRmse(camera), AteRmse(r), 0.003);
  EXPECT_GT(r.at("rpe").at("rotation_deg").at("rmse").get<double>(), 5.0);
  EXPECT_LT(camera.at("rpe").at("rotation_deg").at("rmse").get<double>(), 1.5) << run.log;
}

// As deployed for speed: threaded, the tracker never waiting for the network
// once tracking runs. Keyframes made with carried masks enter the map only
// with their own; geometry is overruled where it would take most of what the
// prior left (before both, 2 of 5 such runs coasted into the crowd and ended
// at 0.05-0.14 m). Threads make each run differ: of 13 runs on an idle
// machine (2026-12-02), 11 gave 0.016-0.019 m with 300/300 posed, one 0.032 m,
// one 0.079 m with 294 posed (lost in the crowd at frame 178, a new map
// merged back). The bounds catch a collapse (0.2-0.5 m, frames without a
// pose), not these: a tighter one would fail CI one run in seven. The
// waiting default is held to 0.022 m above.
TEST(RealCrowdTest, AsynchronousMasksKeepFullModeAccurate) {
  DLSLAM_REQUIRE_SHARED_DATA(sequence, kBonnCrowd);
  const Outcome run = RunOn(sequence, "full", "--async-masks");
  ASSERT_TRUE(run.report.contains("ate")) << run.log;
  const nlohmann::json& r = run.report;
  RecordProperty("ate_mm", static_cast<int>(AteRmse(r) * 1000));
  EXPECT_GE(r.at("frames_posed").get<int>(), 290) << run.log;
  EXPECT_LT(AteRmse(r), 0.1) << run.log;
  EXPECT_GT(r.at("keyframes_held_for_masks").at("held").get<int>(), 0);
  EXPECT_GT(r.at("timing_ms").at("semantic_age_frames").at("count").get<int>(), 100);  // most frames carried
}

// Geometry alone on real people (docs/real-data.md): it must not fall back
// towards the 0.32 m it had before the re-extraction, the inverted-check
// resolution, static-only keyframes (0.11 m) and the agreement radius at
// depth edges. --sequential runs are reproducible bit for bit, but small
// changes move this one chaotically: agreement radius 1, 2, 5 px gave 0.13,
// 0.10, 0.21 m; threaded runs scatter over 0.09-0.23 m with or without the
// prediction gate (which gives 0.126 m here, 0.042 m without; the threaded
// medians 0.134 vs 0.151 m). The bound catches the old failure, not that spread.
TEST(RealCrowdTest, GeometryModeDoesNotRegress) {
  DLSLAM_REQUIRE_SHARED_DATA(sequence, kBonnCrowd);
  const Outcome run = RunOn(sequence, "geometry");
  ASSERT_TRUE(run.report.contains("ate")) << run.log;
  RecordProperty("ate_mm", static_cast<int>(AteRmse(run.report) * 1000));
  EXPECT_EQ(run.report.at("frames_posed").get<int>(), 300);
  EXPECT_LT(AteRmse(run.report), 0.16) << run.log;
  EXPECT_GT(run.report.at("dynamic").at("inverted_checks_resolved").get<int>(), 0);
}

}  // namespace
}  // namespace dlslam
