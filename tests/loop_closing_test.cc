// Loop closing (issue 4) end to end. On the loop preset the camera circles
// the room twice: at the start of the second lap the system must recognise
// the place, close the loop at the right relative pose and end with less
// drift than without loop closing. On sequences that never leave the first
// view (no loop to close) every accepted loop must still be a true one: a
// false loop wrecks the map, so each accepted loop's relative pose is
// checked against the ground truth.

#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/eval/ate.h"
#include "dlslam/synth/camera_path.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"

namespace dlslam {
namespace {

struct LoopRun {
  RunStats stats;
  Trajectory trajectory;  // SLAM world = first camera
  int frames_not_tracked = 0;
};

LoopRun RunSlam(const synth::SynthSequence& sequence, SystemOptions options) {
  SlamSystem slam(sequence.options().camera, options);
  LoopRun run;
  for (int i = 0; i < sequence.size(); ++i) {
    const synth::RenderedFrame f = sequence.Render(i);
    const TrackingResult r = slam.TrackRgbd(f.colour, f.depth, sequence.camera_path()[i].timestamp);
    run.frames_not_tracked += i > 0 && r.state != TrackingState::kOk;
  }
  slam.Shutdown();
  run.stats = slam.Stats();
  run.trajectory = slam.CameraTrajectory();
  return run;
}

std::optional<SE3d> PoseAt(const Trajectory& trajectory, double t) {
  for (const StampedPose& p : trajectory) {
    if (std::abs(p.timestamp - t) < 1e-6) return p.world_from_cam();
  }
  return std::nullopt;
}

// Each loop's relative pose (loop keyframe -> keyframe), estimated at the
// end of the run, against the ground truth's.
void ExpectTrueLoops(const synth::SynthSequence& sequence, const LoopRun& run) {
  for (const LoopEvent& e : run.stats.loop.loops) {
    SCOPED_TRACE(testing::Message() << "loop " << e.loop << " (t=" << e.loop_timestamp << ") <- " << e.current
                                    << " (t=" << e.current_timestamp << ")");
    const auto est_loop = PoseAt(run.trajectory, e.loop_timestamp);
    const auto est_current = PoseAt(run.trajectory, e.current_timestamp);
    const auto gt_loop = PoseAt(sequence.camera_path(), e.loop_timestamp);
    const auto gt_current = PoseAt(sequence.camera_path(), e.current_timestamp);
    ASSERT_TRUE(est_loop && est_current && gt_loop && gt_current);
    const SE3d est = est_loop->Inverse() * *est_current;
    const SE3d gt = gt_loop->Inverse() * *gt_current;
    const SE3d error = gt.Inverse() * est;
    EXPECT_LT(error.translation().norm(), 0.03);
    EXPECT_LT(error.so3().Log().norm() * 180 / M_PI, 1.0);
  }
}

synth::SynthSequence Sequence(synth::Preset preset, int frames, std::uint32_t seed) {
  synth::SynthOptions options;
  options.preset = preset;
  options.frames = frames;
  options.seed = seed;
  return synth::SynthSequence(options);
}

SystemOptions Options(bool loop_closing, bool sequential = true) {
  SystemOptions options;
  options.sequential = sequential;
  options.loop_closing = loop_closing;
  return options;
}

class LoopPresetTest : public ::testing::Test {
 protected:
  // One lap and 2.5 s more: the loop closes early in the second lap, and
  // the frames stay few (rendering costs more than tracking here).
  static constexpr int kFrames = static_cast<int>((synth::kLoopLapS + 2.5) * 30);
  static void SetUpTestSuite() { sequence_ = new synth::SynthSequence(Sequence(synth::Preset::kLoop, kFrames, 1)); }
  static void TearDownTestSuite() {
    delete sequence_;
    sequence_ = nullptr;
  }
  static synth::SynthSequence* sequence_;
};
synth::SynthSequence* LoopPresetTest::sequence_ = nullptr;

TEST_F(LoopPresetTest, ClosesTheLoopAtTheRightPoseAndReducesDrift) {
  const LoopRun with = RunSlam(*sequence_, Options(true));
  const LoopRun without = RunSlam(*sequence_, Options(false));
  EXPECT_EQ(with.frames_not_tracked, 0);
  EXPECT_EQ(without.frames_not_tracked, 0);
  ASSERT_GE(with.stats.loop.loops_closed, 1);
  EXPECT_EQ(without.stats.loop.loops_closed, 0);
  EXPECT_EQ(with.stats.loop.global_bundles_completed, with.stats.loop.loops_closed);  // sequential: never aborted
  const double start = sequence_->camera_path()[0].timestamp;
  for (const LoopEvent& e : with.stats.loop.loops) {
    EXPECT_LT(e.loop_timestamp - start, 3.0) << "the loop keyframe is from the start of the first lap";
    EXPECT_GT(e.current_timestamp - start, synth::kLoopLapS) << "the closing keyframe is from the second lap";
  }
  ExpectTrueLoops(*sequence_, with);
  const double ate_with = eval::ComputeAte(sequence_->camera_path(), with.trajectory).error.rmse;
  const double ate_without = eval::ComputeAte(sequence_->camera_path(), without.trajectory).error.rmse;
  RecordProperty("ate_with_loop_mm", static_cast<int>(std::lround(ate_with * 1000)));
  RecordProperty("ate_without_loop_mm", static_cast<int>(std::lround(ate_without * 1000)));
  EXPECT_LT(ate_with, ate_without);
}

// With the threads (detection while mapping runs; the global bundle
// adjustment in the background): run under TSan in the sanitizer build.
TEST_F(LoopPresetTest, ClosesTheLoopWithTheThreads) {
  const LoopRun run = RunSlam(*sequence_, Options(true, /*sequential=*/false));
  EXPECT_EQ(run.frames_not_tracked, 0);
  EXPECT_GE(run.stats.loop.loops_closed, 1);
  ExpectTrueLoops(*sequence_, run);
}

// Sequences that never leave their first view: whatever loop is accepted
// must be a true one.
TEST(LoopClosingTest, NoFalseLoopsWithoutARevisit) {
  for (const synth::Preset preset : {synth::Preset::kStatic, synth::Preset::kSittingStatic}) {
    SCOPED_TRACE(synth::PresetName(preset));
    const synth::SynthSequence sequence = Sequence(preset, 300, 3);
    const LoopRun run = RunSlam(sequence, Options(true));
    EXPECT_EQ(run.frames_not_tracked, 0);
    ExpectTrueLoops(sequence, run);
    RecordProperty(synth::PresetName(preset) + "_loops", run.stats.loop.loops_closed);
  }
}

}  // namespace
}  // namespace dlslam
