// End to end on a synthetic walking sequence: the dynamic stage in the full
// system (sequential mode, reproducible), against the renderer's ground
// truth: which keypoints moved, and where the camera was.

#include <gtest/gtest.h>

#include <vector>

#include "dlslam/eval/ate.h"
#include "dlslam/synth/actors.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/system/slam_system.h"

namespace dlslam {
namespace {

struct Rendered {
  double timestamp = 0.0;
  cv::Mat colour, depth;
  cv::Mat moving;  // 255 where a surface moved (the mask's moving bit)
  cv::Mat person;  // 255 on people, moving or not: a perfect network's prior
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
      for (int y = 0; y < f.mask.rows; ++y) {
        for (int x = 0; x < f.mask.cols; ++x) {
          const std::uint8_t v = f.mask.at<std::uint8_t>(y, x);
          r.moving.at<std::uint8_t>(y, x) = synth::MaskMoving(v) ? 255 : 0;
          r.person.at<std::uint8_t>(y, x) = synth::MaskClass(v) == synth::kClassPerson ? 255 : 0;
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

  static Outcome Run(DynamicMode mode, dynamic::SearchKind search = dynamic::SearchKind::kExhaustive) {
    SystemOptions options;
    options.sequential = true;
    options.dynamic.mode = mode;
    options.dynamic.geometry.search = search;
    SlamSystem slam(*camera_, options);
    for (const Rendered& f : *frames_) {
      DynamicInputs inputs;
      inputs.semantic_prior = [&f] { return f.person; };
      inputs.moving_truth = f.moving;
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

TEST_F(DynamicPipelineTest, GeometryFindsTheWalkersAndSavesTheTrajectory) {
  const Outcome orb = Run(DynamicMode::kOrb);
  const Outcome geometry = Run(DynamicMode::kGeometry);
  RecordProperty("ate_orb", std::to_string(orb.ate_rmse));
  RecordProperty("ate_geometry", std::to_string(geometry.ate_rmse));
  const DynamicStats& d = geometry.stats.dynamic;
  ASSERT_EQ(d.frames_with_truth, kFrames);
  ASSERT_TRUE(d.precision() && d.recall());
  std::printf("orb ATE %.4f m; geometry ATE %.4f m, precision %.3f recall %.3f, tested %lld, removed %lld\n",
              orb.ate_rmse, geometry.ate_rmse, *d.precision(), *d.recall(),
              static_cast<long long>(d.keypoints_tested), static_cast<long long>(d.keypoints_removed));
  EXPECT_EQ(orb.stats.dynamic.keypoints_removed, 0);
  EXPECT_EQ(geometry.stats.frames_tracked, kFrames);
  EXPECT_GT(d.keypoints_dynamic, 0);
}

TEST_F(DynamicPipelineTest, AntColonyTestsFewerPoints) {
  const Outcome exhaustive = Run(DynamicMode::kGeometry, dynamic::SearchKind::kExhaustive);
  const Outcome ant = Run(DynamicMode::kGeometry, dynamic::SearchKind::kAntColony);
  const DynamicStats& e = exhaustive.stats.dynamic;
  const DynamicStats& a = ant.stats.dynamic;
  std::printf("exhaustive: tested %lld recall %.3f ATE %.4f; ant: tested %lld recall %.3f ATE %.4f\n",
              static_cast<long long>(e.keypoints_tested), e.recall().value_or(-1), exhaustive.ate_rmse,
              static_cast<long long>(a.keypoints_tested), a.recall().value_or(-1), ant.ate_rmse);
  EXPECT_LT(a.keypoints_tested, e.keypoints_tested);
}

TEST_F(DynamicPipelineTest, FullModeWithAPerfectPrior) {
  const Outcome full = Run(DynamicMode::kFull);
  const Outcome semantic = Run(DynamicMode::kSemantic);
  const DynamicStats& f = full.stats.dynamic;
  const DynamicStats& s = semantic.stats.dynamic;
  std::printf("full: ATE %.4f precision %.3f recall %.3f; semantic: ATE %.4f precision %.3f recall %.3f\n",
              full.ate_rmse, f.precision().value_or(-1), f.recall().value_or(-1), semantic.ate_rmse,
              s.precision().value_or(-1), s.recall().value_or(-1));
  EXPECT_EQ(full.stats.frames_tracked, kFrames);
}

}  // namespace
}  // namespace dlslam
