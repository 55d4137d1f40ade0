#include "dlslam/mapping/local_mapper.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/tracking/tracker.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

SE3d CamFromWorld(int i) {
  const double t = i / 30.0;
  Vector6d xi;
  xi << 0.5 * std::sin(0.7 * t), 0.1 * std::sin(1.1 * t), 0.4 * std::sin(0.4 * t), 0.05 * std::sin(0.6 * t),
      0.3 * std::sin(0.5 * t), 0.02 * std::sin(t);
  return SE3d::Exp(xi).Inverse();
}

struct RunResult {
  std::vector<SE3d> poses;
  double max_error = 0;
  LocalMappingStats stats;
  std::size_t keyframes = 0;
};

RunResult RunSequence(bool threaded, bool bundle_adjustment, int frames, double max_depth = 20.0,
                      LocalMapperOptions options = {}, int min_init_points = 500) {
  auto scene = testing::LandmarkScene::Room(6000, 8);
  scene.max_depth = max_depth;
  Map map;
  TrackerOptions tracker_options;
  tracker_options.min_init_points = min_init_points;
  Tracker tracker(tracker_options, &map);
  options.bundle_adjustment = bundle_adjustment;
  LocalMapper mapper(options, &map);
  if (threaded) mapper.Start();
  RunResult out;
  for (int i = 0; i < frames; ++i) {
    const SE3d truth = CamFromWorld(i);
    const TrackingResult r = tracker.Track(scene.MakeFrame(truth, i / 30.0, 500 + i, 1.0));
    EXPECT_EQ(r.state, TrackingState::kOk) << "frame " << i;
    if (r.state != TrackingState::kOk) continue;
    if (r.new_keyframe) mapper.Enqueue(r.reference_keyframe);
    out.poses.push_back(*r.cam_from_world);
    const SE3d truth_rel = truth * CamFromWorld(0).Inverse();
    out.max_error = std::max(
        out.max_error, (r.cam_from_world->Inverse().translation() - truth_rel.Inverse().translation()).norm());
  }
  mapper.Stop();
  out.stats = mapper.stats();
  out.keyframes = map.NumKeyFrames();
  return out;
}

TEST(LocalMapper, SequentialRunIsAccurateAndProcessesEveryKeyFrame) {
  const RunResult r = RunSequence(false, true, 200);
  EXPECT_LT(r.max_error, 0.01);
  EXPECT_GT(r.stats.keyframes_processed, 3);
  EXPECT_EQ(static_cast<std::size_t>(r.stats.keyframes_processed - r.stats.keyframes_culled), r.keyframes);
}

TEST(LocalMapper, SequentialModeIsReproducibleBitForBit) {
  const RunResult a = RunSequence(false, true, 90);
  const RunResult b = RunSequence(false, true, 90);
  ASSERT_EQ(a.poses.size(), b.poses.size());
  for (std::size_t i = 0; i < a.poses.size(); ++i) EXPECT_EQ(a.poses[i].matrix(), b.poses[i].matrix());
}

TEST(LocalMapper, ThreadedRunTracksAsWell) {
  const RunResult r = RunSequence(true, true, 200);
  // Threaded, how much bundle adjustment gets done before each frame depends
  // on the scheduler: with the other tests running beside it the worst frame
  // reached 0.0106-0.0142 m in 3 of 24 runs (0.01 bound; before and after
  // the tracker's gated-keyframe change alike), the sequential run's 0.01.
  EXPECT_LT(r.max_error, 0.02);
  EXPECT_GT(r.stats.keyframes_processed, 3);
}

// Keyframes queued while mapping is held, then let go: each bundle
// adjustment with another keyframe behind it yields, unless told not to.
int BundlesYieldedAfterABacklog(int max_in_a_row) {
  auto scene = testing::LandmarkScene::Room(6000, 8);
  Map map;
  Tracker tracker(TrackerOptions{}, &map);
  LocalMapperOptions options;
  options.max_bundle_yields_in_a_row = max_in_a_row;
  LocalMapper mapper(options, &map);
  mapper.Start();
  {
    const PauseGate::Hold hold = mapper.Pause();
    for (int i = 0; i < 300 && mapper.backlog() < 4; ++i) {
      const TrackingResult r = tracker.Track(scene.MakeFrame(CamFromWorld(i), i / 30.0, 500 + i, 1.0));
      if (r.new_keyframe) mapper.Enqueue(r.reference_keyframe);
    }
    EXPECT_GE(mapper.backlog(), 4u);
  }
  mapper.Stop();
  return mapper.stats().bundles_yielded;
}

TEST(LocalMapper, BundleAdjustmentYieldsToAQueuedKeyFrame) {
  // Of 4 queued, the first 3 find another behind them: all 3 yield, or
  // the 1st and 3rd when only one in a row may.
  EXPECT_EQ(BundlesYieldedAfterABacklog(3), 3);
  EXPECT_EQ(BundlesYieldedAfterABacklog(1), 2);
  EXPECT_EQ(BundlesYieldedAfterABacklog(0), 0);
  EXPECT_EQ(RunSequence(false, true, 200).stats.bundles_yielded, 0);  // sequential: never
}

TEST(LocalMapper, WaitForProcessedReturnsOnceTheKeyFramesAreDone) {
  using std::chrono::milliseconds;
  auto scene = testing::LandmarkScene::Room(6000, 8);
  Map map;
  Tracker tracker(TrackerOptions{}, &map);
  LocalMapper mapper(LocalMapperOptions{}, &map);
  mapper.Start();
  std::uint64_t ticket = 0;
  {
    const PauseGate::Hold hold = mapper.Pause();  // nothing is processed meanwhile
    for (int i = 0; i < 300 && ticket < 2; ++i) {
      const TrackingResult r = tracker.Track(scene.MakeFrame(CamFromWorld(i), i / 30.0, 500 + i, 1.0));
      if (r.new_keyframe) ticket = mapper.Enqueue(r.reference_keyframe);
    }
    ASSERT_EQ(ticket, 2u);  // tickets count the keyframes handed over
    EXPECT_FALSE(mapper.WaitForProcessed(1, milliseconds(20)));  // held: times out
  }
  EXPECT_TRUE(mapper.WaitForProcessed(2, milliseconds(60000)));
  EXPECT_EQ(mapper.stats().keyframes_processed, 2);
  EXPECT_FALSE(mapper.WaitForProcessed(3, milliseconds(0)));  // not handed over yet
  mapper.Stop();
}

TEST(LocalMapper, InlineKeyFramesAreProcessedWhenEnqueued) {
  auto scene = testing::LandmarkScene::Room(6000, 8);
  Map map;
  Tracker tracker(TrackerOptions{}, &map);
  LocalMapper mapper(LocalMapperOptions{}, &map);  // not started: sequential
  const TrackingResult r = tracker.Track(scene.MakeFrame(CamFromWorld(0), 0.0, 500, 1.0));
  ASSERT_TRUE(r.new_keyframe);
  EXPECT_EQ(mapper.Enqueue(r.reference_keyframe), 1u);
  EXPECT_TRUE(mapper.WaitForProcessed(1, std::chrono::milliseconds(0)));
}

TEST(LocalMapper, TriangulatesWhereDepthEnds) {
  // A 4.5 m sensor range: the far wall (5 m) has no depth; its points come
  // from triangulation. Fewer points with depth make every pose ~1 cm worse
  // than in the full-depth runs (already over the first frames, before any
  // triangulation), so the bound is looser here.
  const RunResult r = RunSequence(false, true, 90, 4.5, {}, 200);
  EXPECT_GT(r.stats.points_triangulated, 200);
  EXPECT_GT(r.stats.points_fused, 0);
  EXPECT_LT(r.max_error, 0.025);
  LocalMapperOptions without;
  without.triangulation = false;
  without.fusion = false;
  const RunResult plain = RunSequence(false, true, 90, 4.5, without, 200);
  EXPECT_EQ(plain.stats.points_triangulated, 0);
  EXPECT_EQ(plain.stats.points_fused, 0);
  EXPECT_LT(r.max_error, plain.max_error + 0.005);  // the new points do not hurt
}

TEST(LocalMapper, BothBundleSolversTrackAlike) {
  LocalMapperOptions ceres;
  ceres.bundle.solver = BundleSolver::kCeres;
  const RunResult with_ceres = RunSequence(false, true, 60, 20.0, ceres);
  LocalMapperOptions lm;
  lm.bundle.solver = BundleSolver::kLm;
  const RunResult with_lm = RunSequence(false, true, 60, 20.0, lm);
  EXPECT_LT(with_ceres.max_error, 0.01);
  EXPECT_LT(with_lm.max_error, 0.01);
}

TEST(LocalMapperOptions, Check) {
  LocalMapperOptions o;
  o.min_found_ratio = 2;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
