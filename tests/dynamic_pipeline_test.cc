// End to end on a synthetic walking sequence: the dynamic stage in the full
// system (sequential mode, reproducible), against the renderer's ground
// truth: which keypoints moved, and where the camera was.

#include <gtest/gtest.h>

#include <vector>

#include "dlslam/eval/ate.h"
#include "dlslam/synth/actors.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

struct Rendered {
  double timestamp = 0.0;
  cv::Mat colour, depth;
  cv::Mat moving;  // 255 where a surface moved (the mask's moving bit)
  cv::Mat person;  // 255 on people, moving or not: a perfect network's prior
  cv::Mat box;     // 255 on boxes (class "other movable object"), moving or not
};

struct RunSetup {
  DynamicMode mode = DynamicMode::kFull;
  dynamic::SearchKind search = dynamic::SearchKind::kExhaustive;
  bool sequential = true;
  bool box_prior = false;            // the boxes as the movable-class mask
  bool drop_moving_movables = true;  // FusionOptions
  bool truth_on_moving_boxes = false;  // statistics over the moving boxes' keypoints only
  double region_reach_m = 0.0;         // RegionGrowingOptions::max_distance_from_seed_m; 0 = default
};

struct Outcome {
  RunStats stats;
  double ate_rmse = 0.0;
};

class DynamicPipelineTest : public ::testing::Test {
 protected:
  static constexpr int kFrames = 100;

  static void SetUpTestSuite() {
    synth::SynthOptions options;
    options.preset = synth::Preset::kWalkingXyz;
    options.frames = kFrames;
    options.seed = 1;
    const synth::SynthSequence sequence(options);
    frames_ = new std::vector<Rendered>();
    ground_truth_ = new Trajectory(sequence.camera_path());
    camera_ = new CameraIntrinsics(options.camera);
    for (int i = 0; i < sequence.size(); ++i) {
      synth::RenderedFrame f = sequence.Render(i);
      Rendered r;
      r.timestamp = sequence.camera_path()[i].timestamp;
      r.colour = f.colour;
      r.depth = f.depth;
      r.moving = cv::Mat(f.mask.size(), CV_8UC1);
      r.person = cv::Mat(f.mask.size(), CV_8UC1);
      r.box = cv::Mat(f.mask.size(), CV_8UC1);
      for (int y = 0; y < f.mask.rows; ++y) {
        for (int x = 0; x < f.mask.cols; ++x) {
          const std::uint8_t v = f.mask.at<std::uint8_t>(y, x);
          r.moving.at<std::uint8_t>(y, x) = synth::MaskMoving(v) ? 255 : 0;
          r.person.at<std::uint8_t>(y, x) = synth::MaskClass(v) == synth::kClassPerson ? 255 : 0;
          r.box.at<std::uint8_t>(y, x) = synth::MaskClass(v) == synth::kClassMovable ? 255 : 0;
        }
      }
      frames_->push_back(std::move(r));
    }
  }
  static void TearDownTestSuite() {
    delete frames_;
    delete ground_truth_;
    delete camera_;
  }

  static Outcome Run(DynamicMode mode, dynamic::SearchKind search = dynamic::SearchKind::kExhaustive,
                     bool sequential = true) {
    return Run(RunSetup{.mode = mode, .search = search, .sequential = sequential});
  }

  static Outcome Run(const RunSetup& setup) {
    SystemOptions options;
    options.sequential = setup.sequential;
    options.dynamic.mode = setup.mode;
    options.semantic.network = false;  // each frame brings its rendered person mask
    options.dynamic.geometry.search = setup.search;
    options.dynamic.fusion.drop_moving_movables = setup.drop_moving_movables;
    if (setup.region_reach_m > 0) options.dynamic.geometry.region.max_distance_from_seed_m = setup.region_reach_m;
    SlamSystem slam(*camera_, options);
    for (const Rendered& f : *frames_) {
      DynamicInputs inputs;
      inputs.semantic_prior = [&f, &setup] {
        return dynamic::SemanticMasks{f.person, setup.box_prior ? f.box : cv::Mat()};
      };
      inputs.moving_truth = setup.truth_on_moving_boxes ? (f.moving & f.box) : f.moving;
      slam.TrackRgbd(f.colour, f.depth, f.timestamp, inputs);
    }
    slam.Shutdown();
    Outcome out;
    out.stats = slam.Stats();
    out.ate_rmse = eval::ComputeAte(*ground_truth_, slam.CameraTrajectory()).error.rmse;
    return out;
  }

  static std::vector<Rendered>* frames_;
  static Trajectory* ground_truth_;
  static CameraIntrinsics* camera_;
};

std::vector<Rendered>* DynamicPipelineTest::frames_ = nullptr;
Trajectory* DynamicPipelineTest::ground_truth_ = nullptr;
CameraIntrinsics* DynamicPipelineTest::camera_ = nullptr;

// Bounds, and why:
// - ATE: the ORB baseline follows the walkers (0.87 m on 300 frames of this
//   preset, docs/synth.md; 0.50 m on these frames, 0.039 m since gated
//   frames make no keyframes), while removing the moving pixels by ground
//   truth gives 3.6 mm; geometry must be close to the latter: under 2 cm
//   (DynaSLAM's 1.6 cm on the real walking_xyz) and several times better
//   than orb (0.0057 m: 6.8x).
// - Precision: removing the same number of keypoints at random would hit
//   moving ones at the base rate (moving / all keypoints); geometry must do
//   at least twice as well. (Its removals include the still parts of
//   people and the dilated silhouettes, so it is well below 1.)
// - Recall: at least 80 % of the keypoints on moving surfaces removed.
TEST_F(DynamicPipelineTest, GeometryFindsTheWalkersAndSavesTheTrajectory) {
  const Outcome orb = Run(DynamicMode::kOrb);
  const Outcome geometry = Run(DynamicMode::kGeometry);
  const DynamicStats& d = geometry.stats.dynamic;
  ASSERT_EQ(d.frames_with_truth, kFrames);
  ASSERT_TRUE(d.precision() && d.recall());
  const double base_rate =
      static_cast<double>(d.true_positives + d.false_negatives) / static_cast<double>(d.keypoints_total);
  std::printf("orb ATE %.4f m; geometry ATE %.4f m, precision %.3f (base rate %.3f) recall %.3f\n", orb.ate_rmse,
              geometry.ate_rmse, *d.precision(), base_rate, *d.recall());
  EXPECT_EQ(orb.stats.dynamic.keypoints_removed, 0);
  EXPECT_EQ(orb.stats.dynamic.recall(), 0.0);
  EXPECT_EQ(geometry.stats.frames_tracked, kFrames);
  EXPECT_LT(geometry.ate_rmse, 0.02);
  EXPECT_GT(orb.ate_rmse, 4 * geometry.ate_rmse);
  EXPECT_GT(*d.precision(), 2 * base_rate);
  EXPECT_GT(*d.recall(), 0.8);
  EXPECT_LE(d.keypoints_dynamic, d.keypoints_tested);
  EXPECT_EQ(d.frames_with_geometry, kFrames - 1);  // all but the first, which has no keyframe before it
}

// The ant colony search must test far fewer points (the issue asks for far
// fewer; we hold it to three quarters) and find nearly the same keypoints:
// recall within 5 points of the exhaustive search's, trajectory as good.
TEST_F(DynamicPipelineTest, AntColonyTestsFewerPointsWithNearlyTheSameRecall) {
  const Outcome exhaustive = Run(DynamicMode::kGeometry, dynamic::SearchKind::kExhaustive);
  const Outcome ant = Run(DynamicMode::kGeometry, dynamic::SearchKind::kAntColony);
  const DynamicStats& e = exhaustive.stats.dynamic;
  const DynamicStats& a = ant.stats.dynamic;
  ASSERT_TRUE(e.recall() && a.recall());
  std::printf("exhaustive: tested %lld recall %.3f ATE %.4f; ant: tested %lld recall %.3f ATE %.4f\n",
              static_cast<long long>(e.keypoints_tested), *e.recall(), exhaustive.ate_rmse,
              static_cast<long long>(a.keypoints_tested), *a.recall(), ant.ate_rmse);
  EXPECT_LT(a.keypoints_tested, 0.75 * static_cast<double>(e.keypoints_tested));
  EXPECT_GT(*a.recall(), *e.recall() - 0.05);
  EXPECT_LT(ant.ate_rmse, 0.02);
}

// A perfect network prior (people, moving or not) with geometry. The scene
// also has boxes that are carried or slid: a class the prior does not know,
// so the semantic mode alone misses them and only geometry can find them.
TEST_F(DynamicPipelineTest, FullModeAddsWhatThePriorDoesNotKnow) {
  const Outcome full = Run(DynamicMode::kFull);
  const Outcome semantic = Run(DynamicMode::kSemantic);
  const DynamicStats& f = full.stats.dynamic;
  const DynamicStats& s = semantic.stats.dynamic;
  ASSERT_TRUE(f.recall() && s.recall() && f.precision());
  std::printf("full: ATE %.4f precision %.3f recall %.3f; semantic: ATE %.4f precision %.3f recall %.3f\n",
              full.ate_rmse, *f.precision(), *f.recall(), semantic.ate_rmse, s.precision().value_or(-1),
              *s.recall());
  EXPECT_EQ(full.stats.frames_tracked, kFrames);
  EXPECT_LT(full.ate_rmse, 0.02);
  // Union with the prior: at least as complete as geometry's 80 %, and
  // strictly more complete than the prior alone (the boxes).
  EXPECT_GT(*f.recall(), 0.8);
  EXPECT_GT(*f.recall(), *s.recall());
  EXPECT_GT(*s.image_share_removed(), 0.01);  // the people, left out of the extraction
  EXPECT_EQ(s.keypoints_tested, 0);
}

// The carried box as a movable class (a network's chair): once geometry
// sees it move, the whole box goes, not only the region grown around its
// moving points. Statistics here count the moving box's keypoints only.
// Regions grow 5 cm from their seeds here instead of 45 cm, so that the box
// stands in for an object larger than the growth limit (a pushed table):
// with the default reach, regions already cover this small box.
TEST_F(DynamicPipelineTest, AMovingMovableObjectIsDroppedWhole) {
  RunSetup setup{
      .mode = DynamicMode::kFull, .box_prior = true, .truth_on_moving_boxes = true, .region_reach_m = 0.05};
  const Outcome whole = Run(setup);
  setup.drop_moving_movables = false;
  const Outcome grown = Run(setup);
  const DynamicStats& w = whole.stats.dynamic;
  const DynamicStats& g = grown.stats.dynamic;
  ASSERT_TRUE(w.recall() && g.recall());
  std::printf("moving box keypoints: recall %.3f (%lld missed) dropped whole vs %.3f (%lld missed) grown only; "
              "%lld segments dropped; ATE %.4f vs %.4f\n",
              *w.recall(), static_cast<long long>(w.false_negatives), *g.recall(),
              static_cast<long long>(g.false_negatives), static_cast<long long>(w.movable_segments_dropped),
              whole.ate_rmse, grown.ate_rmse);
  EXPECT_GT(w.movable_segments_dropped, 0);
  EXPECT_EQ(g.movable_segments_dropped, 0);
  EXPECT_LT(w.false_negatives, g.false_negatives);
  EXPECT_EQ(whole.stats.frames_tracked, kFrames);
  EXPECT_LT(whole.ate_rmse, 0.02);
}

// With the local-mapping thread running beside the dynamic stage (it reads
// keyframes and culls map points while mapping refines them): the same
// quality, not bit-reproducible. Under TSan this is the race check.
TEST_F(DynamicPipelineTest, FullModeWithTheMappingThread) {
  const Outcome full = Run(DynamicMode::kFull, dynamic::SearchKind::kAntColony, /*sequential=*/false);
  EXPECT_EQ(full.stats.frames_tracked, kFrames);
  EXPECT_LT(full.ate_rmse, 0.02);
  EXPECT_GT(full.stats.dynamic.recall().value_or(0), 0.8);
}

TEST_F(DynamicPipelineTest, TheLibraryRunsTheNetworkInItsSemanticThread) {
  // No prior per frame: the system segments each frame itself (the tiny
  // identity-colour model of the fixtures stands in for the network), at
  // the rate asked for, and times it as stage "semantic". Threaded, as
  // deployed: the semantic, mapping and loop threads together (TSan).
  SystemOptions options;
  options.sequential = false;
  options.dynamic.mode = DynamicMode::kSemantic;
  options.semantic.segmenter.model_path = testing::FixturePath("semantic/identity_rgb.onnx");
  options.semantic.worker.segment_every = 2;
  SlamSystem slam(*camera_, options);
  const int frames = 20;
  for (int i = 0; i < frames; ++i) {
    const Rendered& f = (*frames_)[static_cast<std::size_t>(i)];
    slam.TrackRgbd(f.colour, f.depth, f.timestamp);
  }
  slam.Shutdown();
  const RunStats stats = slam.Stats();
  ASSERT_EQ(stats.timing_ms.count("semantic"), 1u);
  EXPECT_EQ(stats.timing_ms.at("semantic").count, static_cast<std::size_t>(frames));
  // Threaded: under load a frame may coast while mapping lags; none is lost.
  EXPECT_EQ(stats.frames_tracked + stats.frames_coasted, frames)
      << "coasted " << stats.frames_coasted << ", jumps refused " << stats.jumps_refused;
  EXPECT_GE(stats.frames_tracked, frames - 2) << "jumps refused " << stats.jumps_refused;

  // Asynchronous masks: the first frame waits for its own (the map's
  // foundation), the others take the newest finished masks carried to them
  // (the crowd rule off: this model marks much of every frame).
  options.semantic.wait_for_masks = false;
  options.semantic.wait_when_removed_share = 1.0;
  const auto run_async = [&] {
    SlamSystem async(*camera_, options);
    for (int i = 0; i < frames; ++i) {
      const Rendered& f = (*frames_)[static_cast<std::size_t>(i)];
      async.TrackRgbd(f.colour, f.depth, f.timestamp);
    }
    async.Shutdown();
    return async.Stats();
  };
  const RunStats async_stats = run_async();
  EXPECT_EQ(async_stats.frames_tracked + async_stats.frames_coasted, frames);
  ASSERT_EQ(async_stats.timing_ms.count("semantic_age_frames"), 1u);
  // All but the first carried, except after a frame that coasted (it waits).
  EXPECT_LE(async_stats.timing_ms.at("semantic_age_frames").count, static_cast<std::size_t>(frames - 1));
  EXPECT_GE(async_stats.timing_ms.at("semantic_age_frames").count,
            static_cast<std::size_t>(frames - 1 - 2 * async_stats.frames_coasted));
  // The network's time, once per frame it segmented: the first, and those it was free for.
  EXPECT_GE(async_stats.timing_ms.at("semantic").count, 1u);
  EXPECT_LE(async_stats.timing_ms.at("semantic").count, static_cast<std::size_t>(frames));
  // With the crowd rule at a share every frame reaches, every frame waits for its own masks.
  options.semantic.wait_when_removed_share = 1e-6;
  const RunStats crowded = run_async();
  EXPECT_EQ(crowded.frames_tracked + crowded.frames_coasted, frames);
  EXPECT_EQ(crowded.timing_ms.count("semantic_age_frames"), 0u);
  EXPECT_EQ(crowded.timing_ms.at("semantic").count, static_cast<std::size_t>(frames));
  options.semantic.wait_for_masks = true;

  // A broken model is refused when the system is made, naming the file.
  options.semantic.segmenter.model_path = testing::FixturePath("semantic/missing.onnx");
  EXPECT_THROW(SlamSystem(*camera_, options), InputError);
  options.semantic.network = false;  // the caller brings the priors: no model is loaded
  EXPECT_NO_THROW(SlamSystem(*camera_, options));
}

TEST_F(DynamicPipelineTest, FramesSegmentedAheadTrackExactlyAsSegmentedInTurn) {
  // SegmentAhead only starts the network earlier: the masks, and so the
  // trajectory (sequential: reproducible bit for bit), are the same. A frame
  // segmented ahead but never tracked (6) is dropped; an out-of-order call
  // is ignored.
  SystemOptions options;
  options.sequential = true;
  options.dynamic.mode = DynamicMode::kSemantic;
  options.semantic.segmenter.model_path = testing::FixturePath("semantic/identity_rgb.onnx");
  const int frames = 16;
  const auto run = [&](bool ahead) {
    SlamSystem slam(*camera_, options);
    if (ahead) slam.SegmentAhead((*frames_)[0].colour, (*frames_)[0].timestamp);
    for (int i = 0; i < frames; ++i) {
      if (i == 6) continue;
      const Rendered& f = (*frames_)[static_cast<std::size_t>(i)];
      if (ahead && i + 1 < frames) {
        const Rendered& next = (*frames_)[static_cast<std::size_t>(i + 1)];
        slam.SegmentAhead(next.colour, next.timestamp);
        slam.SegmentAhead(f.colour, f.timestamp);  // older than the last one ahead: ignored
      }
      slam.TrackRgbd(f.colour, f.depth, f.timestamp);
    }
    slam.Shutdown();
    return std::make_tuple(slam.Stats(), slam.CameraTrajectory(), slam.FrameSources());
  };
  const auto [in_turn, in_turn_trajectory, in_turn_sources] = run(false);
  const auto [ahead, ahead_trajectory, ahead_sources] = run(true);
  EXPECT_EQ(in_turn.frames_segmented_ahead, 0);
  // All tracked frames but 7 (its turn to be segmented ahead came while 6 was skipped).
  EXPECT_EQ(ahead.frames_segmented_ahead, frames - 2);
  EXPECT_EQ(ahead.timing_ms.at("semantic").count, static_cast<std::size_t>(frames - 1));
  ASSERT_EQ(ahead_trajectory.size(), in_turn_trajectory.size());
  ASSERT_EQ(ahead_trajectory.size(), static_cast<std::size_t>(frames - 1));
  for (std::size_t i = 0; i < ahead_trajectory.size(); ++i) {
    EXPECT_EQ(ahead_trajectory[i].translation, in_turn_trajectory[i].translation) << i;
    EXPECT_EQ(ahead_trajectory[i].rotation.coeffs(), in_turn_trajectory[i].rotation.coeffs()) << i;
  }
  // Asynchronous masks: a frame waits for its own masks when tracking was
  // not ok before it (never crowded here), and the frame after a waiting one
  // is segmented ahead; the others carry the newest masks. Which frames wait
  // depends on the carried masks, i.e. on the network's timing: the expected
  // count follows the run's pose sources.
  options.semantic.wait_for_masks = false;
  options.semantic.wait_when_removed_share = 1.0;
  const auto [asynchronous, async_trajectory, sources] = run(true);
  ASSERT_EQ(sources.size(), static_cast<std::size_t>(frames - 1));  // frame 6 is skipped
  const auto ok = [](PoseSource s) {
    return s == PoseSource::kTracked || s == PoseSource::kRelocalized || s == PoseSource::kNewMap;
  };
  int expected_ahead = 0;
  for (std::size_t k = 1; k < sources.size(); ++k) {
    const bool previous_waited = k == 1 || !ok(sources[k - 2].source);
    const bool after_the_skip = k == 6;  // frame 7: the frame ahead of 5 was 6, never tracked
    expected_ahead += previous_waited && !after_the_skip;
  }
  EXPECT_EQ(asynchronous.frames_segmented_ahead, expected_ahead);
  EXPECT_GE(asynchronous.frames_segmented_ahead, asynchronous.frames_waiting + 1);
  EXPECT_LT(asynchronous.frames_segmented_ahead, frames / 2);
  // A wrong size is an error naming the frame.
  options.semantic.wait_for_masks = true;
  SlamSystem slam(*camera_, options);
  EXPECT_THROW(slam.SegmentAhead(cv::Mat(10, 10, CV_8UC3), 1.5), Error);
}

}  // namespace
}  // namespace dlslam
