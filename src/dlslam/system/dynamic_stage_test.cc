#include "dlslam/system/dynamic_stage.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

const CameraIntrinsics kCamera = CameraPreset("freiburg3");

// Keypoints on a 32 px grid (centres at 16 + 32 k), no depth.
std::shared_ptr<Frame> GridFrame(const cv::Mat& depth = cv::Mat()) {
  std::vector<cv::KeyPoint> keypoints;
  for (int y = 16; y < kCamera.height; y += 32) {
    for (int x = 16; x < kCamera.width; x += 32) keypoints.emplace_back(cv::Point2f(x, y), 31.f);
  }
  const cv::Mat descriptors(static_cast<int>(keypoints.size()), 32, CV_8UC1, cv::Scalar(0));
  return std::make_shared<Frame>(Frame::Create(0.0, keypoints, descriptors, depth, kCamera, ScalePyramid()));
}

cv::Mat Rectangle(int x0, int y0, int x1, int y1) {
  cv::Mat mask(kCamera.height, kCamera.width, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(x0, y0, x1 - x0, y1 - y0)).setTo(255);
  return mask;
}

// Grid keypoints (16 + 32 k) inside [x0, x1) x [y0, y1).
int GridPointsIn(int x0, int y0, int x1, int y1) {
  const auto count = [](int lo, int hi) {
    int n = 0;
    for (int c = 16; c < 640; c += 32) n += c >= lo && c < hi;
    return n;
  };
  return count(x0, x1) * count(y0, y1);
}

class DynamicStageTest : public ::testing::Test {
 protected:
  DynamicStage MakeStage(DynamicMode mode, double dilation_px = 0.0) {
    DynamicOptions options;
    options.mode = mode;
    options.fusion.dilation_px = dilation_px;
    return DynamicStage(options, kCamera, &map_, &tracker_, &timings_);
  }

  Map map_;
  Tracker tracker_{TrackerOptions(), &map_};
  StageTimings timings_;
};

TEST_F(DynamicStageTest, SemanticModeRemovesThePriorAndCountsAgainstTruth) {
  DynamicStage stage = MakeStage(DynamicMode::kSemantic);
  auto frame = GridFrame();
  DynamicInputs inputs;
  // Movable objects are static structure until geometry sees them move:
  // without geometry (this mode) they stay.
  inputs.semantic_prior = [] {
    return dynamic::SemanticMasks{Rectangle(100, 100, 300, 200), Rectangle(400, 300, 600, 400)};
  };
  inputs.moving_truth = Rectangle(200, 100, 400, 200);
  const DynamicRemoval removal = stage.Process(*frame, cv::Mat(), inputs);
  const int removed = GridPointsIn(100, 100, 300, 200);
  const std::vector<bool> on = frame->OnMask(removal.mask);
  EXPECT_EQ(std::count(on.begin(), on.end(), true), removed);
  EXPECT_EQ(removal.keypoints, on);
  EXPECT_EQ(removal.count, static_cast<std::size_t>(removed));
  EXPECT_EQ(frame->WithoutMasked(removal.mask).size(), frame->size() - removed);
  const DynamicStats& s = stage.stats();
  EXPECT_EQ(s.keypoints_removed, removed);
  EXPECT_EQ(s.frames_with_truth, 1);
  EXPECT_EQ(s.true_positives, GridPointsIn(200, 100, 300, 200));
  EXPECT_EQ(s.false_positives, GridPointsIn(100, 100, 200, 200));
  EXPECT_EQ(s.false_negatives, GridPointsIn(300, 100, 400, 200));
  ASSERT_TRUE(s.precision() && s.recall());
  EXPECT_NEAR(*s.precision(), 0.5, 0.1);
  EXPECT_DOUBLE_EQ(*s.precision(), static_cast<double>(s.true_positives) / removed);
  EXPECT_EQ(s.keypoints_tested, 0);  // no geometry in this mode
  EXPECT_EQ(s.keypoints_total, static_cast<std::int64_t>(frame->size()));
  EXPECT_EQ(timings_.Summaries().at("semantic_wait").count, 1u);
}

TEST_F(DynamicStageTest, RemovalMaskIsDilated) {
  DynamicStage stage = MakeStage(DynamicMode::kSemantic, /*dilation_px=*/5.0);
  auto frame = GridFrame();
  DynamicInputs inputs;
  // Ends 3 px left of the column of keypoints at x = 208: dilation reaches it.
  inputs.semantic_prior = [] { return dynamic::SemanticMasks{Rectangle(100, 100, 205, 200)}; };
  stage.Process(*frame, cv::Mat(), inputs);
  EXPECT_EQ(stage.stats().keypoints_removed, GridPointsIn(100, 100, 209, 200));
}

TEST_F(DynamicStageTest, OrbModeRemovesNothingAndNeverAsksForThePrior) {
  DynamicStage stage = MakeStage(DynamicMode::kOrb);
  auto frame = GridFrame();
  bool asked = false;
  DynamicInputs inputs;
  inputs.semantic_prior = [&asked] {
    asked = true;
    return dynamic::SemanticMasks{Rectangle(0, 0, 640, 480)};
  };
  inputs.moving_truth = Rectangle(200, 100, 400, 200);
  const DynamicRemoval removal = stage.Process(*frame, cv::Mat(), inputs);
  EXPECT_TRUE(removal.mask.empty());
  EXPECT_EQ(removal.count, 0u);
  EXPECT_FALSE(asked);
  const DynamicStats& s = stage.stats();
  EXPECT_EQ(s.keypoints_removed, 0);
  EXPECT_EQ(s.false_negatives, GridPointsIn(200, 100, 400, 200));
  EXPECT_FALSE(s.precision().has_value());  // nothing removed
  EXPECT_EQ(s.recall(), 0.0);
}

TEST_F(DynamicStageTest, GeometryWaitsForTracking) {
  DynamicStage stage = MakeStage(DynamicMode::kGeometry);
  auto frame = GridFrame();
  stage.Process(*frame, cv::Mat(kCamera.height, kCamera.width, CV_32FC1, cv::Scalar(2.0)), DynamicInputs{});
  EXPECT_EQ(stage.stats().frames_with_geometry, 0);  // the tracker has no pose yet
  EXPECT_EQ(stage.stats().keypoints_removed, 0);
  EXPECT_FALSE(stage.stats().recall().has_value());  // no ground truth
}

TEST_F(DynamicStageTest, ThePriorAloneIsFusedBeforeExtractionAndFinalUnderUnion) {
  DynamicInputs inputs;
  inputs.semantic_prior = [] { return dynamic::SemanticMasks{Rectangle(100, 100, 300, 200)}; };
  DynamicStage full = MakeStage(DynamicMode::kFull, /*dilation_px=*/5.0);
  const DynamicPrior prior = full.TakePrior(inputs, cv::Mat());
  ASSERT_FALSE(prior.removal.empty());
  EXPECT_TRUE(prior.final);  // union: the fused mask holds the prior whatever geometry says
  // Dilated as the fused mask is: 5 px around the rectangle, not 6.
  EXPECT_EQ(prior.removal.at<uchar>(150, 95), 255);
  EXPECT_EQ(prior.removal.at<uchar>(150, 94), 0);
  EXPECT_NEAR(prior.removed_share(), cv::countNonZero(prior.removal) / (640.0 * 480.0), 1e-12);
  // Process with that prior removes what Process with the inputs removes.
  auto frame = GridFrame();
  const DynamicRemoval from_prior = full.Process(*frame, cv::Mat(), prior);
  const DynamicRemoval from_inputs = full.Process(*frame, cv::Mat(), inputs);
  EXPECT_EQ(cv::countNonZero(from_prior.mask != from_inputs.mask), 0);
  EXPECT_EQ(cv::countNonZero(from_prior.mask != prior.removal), 0);  // no geometry without depth

  DynamicStage semantic = MakeStage(DynamicMode::kSemantic);
  EXPECT_TRUE(semantic.TakePrior(inputs, cv::Mat()).final);
  DynamicOptions confirms;
  confirms.mode = DynamicMode::kFull;
  confirms.fusion.policy = dynamic::FusionPolicy::kGeometryConfirms;
  DynamicStage confirming(confirms, kCamera, &map_, &tracker_, &timings_);
  const DynamicPrior maybe = confirming.TakePrior(inputs, cv::Mat());
  EXPECT_FALSE(maybe.removal.empty());
  EXPECT_FALSE(maybe.final);  // geometry may keep the segment: its keypoints must be extracted

  // No prior, or one without a pixel: nothing to leave out.
  inputs.semantic_prior = [] { return dynamic::SemanticMasks{Rectangle(0, 0, 0, 0)}; };
  EXPECT_TRUE(full.TakePrior(inputs, cv::Mat()).removal.empty());
  EXPECT_TRUE(full.TakePrior(DynamicInputs{}, cv::Mat()).removal.empty());
  bool asked = false;
  inputs.semantic_prior = [&asked] {
    asked = true;
    return dynamic::SemanticMasks{};
  };
  EXPECT_TRUE(MakeStage(DynamicMode::kGeometry).TakePrior(inputs, cv::Mat()).removal.empty());
  EXPECT_FALSE(asked);  // geometry mode never waits for a network
}

TEST(GeometryTakesTooMuch, ComparesWithWhatThePriorLeft) {
  auto frame = GridFrame();  // 20 x 15 grid keypoints
  const cv::Mat prior = Rectangle(0, 0, 320, 480);  // the left half: 150 left
  // Geometry adds 4 of the 10 right-hand columns (60 of 150), then 6 (90 of 150).
  EXPECT_FALSE(GeometryTakesTooMuch(*frame, prior, Rectangle(0, 0, 448, 480), 0.5));
  EXPECT_TRUE(GeometryTakesTooMuch(*frame, prior, Rectangle(0, 0, 512, 480), 0.5));
  EXPECT_TRUE(GeometryTakesTooMuch(*frame, prior, Rectangle(0, 0, 448, 480), 0.35));
  EXPECT_FALSE(GeometryTakesTooMuch(*frame, prior, Rectangle(0, 0, 640, 480), 1.0));  // 1: never
  // No prior pixel: the share of all keypoints. Keypoints already left out
  // of the extraction (none in the prior) count the same way.
  EXPECT_TRUE(GeometryTakesTooMuch(*frame, cv::Mat(), Rectangle(0, 0, 352, 480), 0.5));  // 165 of 300
  EXPECT_FALSE(GeometryTakesTooMuch(*frame, cv::Mat(), Rectangle(0, 0, 288, 480), 0.5));  // 135 of 300
  const Frame outside = frame->WithoutMasked(prior);
  EXPECT_FALSE(GeometryTakesTooMuch(outside, prior, Rectangle(0, 0, 448, 480), 0.5));
  EXPECT_TRUE(GeometryTakesTooMuch(outside, prior, Rectangle(0, 0, 512, 480), 0.5));
}

TEST_F(DynamicStageTest, BadMasksAreErrors) {
  DynamicStage stage = MakeStage(DynamicMode::kFull);
  auto frame = GridFrame();
  DynamicInputs inputs;
  inputs.semantic_prior = [] { return dynamic::SemanticMasks{cv::Mat(240, 320, CV_8UC1, cv::Scalar(0))}; };
  EXPECT_THROW(stage.Process(*frame, cv::Mat(), inputs), Error);
  inputs.semantic_prior = [] { return dynamic::SemanticMasks{cv::Mat(480, 640, CV_16UC1, cv::Scalar(0))}; };
  EXPECT_THROW(stage.Process(*frame, cv::Mat(), inputs), Error);
  inputs.semantic_prior = [] {
    return dynamic::SemanticMasks{cv::Mat(480, 640, CV_8UC1, cv::Scalar(0)), cv::Mat(480, 600, CV_8UC1, cv::Scalar(0))};
  };
  EXPECT_THROW(stage.Process(*frame, cv::Mat(), inputs), Error);
  inputs.semantic_prior = nullptr;
  inputs.moving_truth = cv::Mat(480, 640, CV_8UC3, cv::Scalar(0));
  EXPECT_THROW(stage.Process(*frame, cv::Mat(), inputs), Error);
}

TEST(MakeReferenceView, KeypointsWithDepthInWorldCoordinates) {
  cv::Mat depth(kCamera.height, kCamera.width, CV_32FC1, cv::Scalar(0));
  depth(cv::Rect(0, 0, 320, 480)).setTo(2.5);  // left half has depth
  const auto frame = GridFrame(depth);
  Eigen::Matrix<double, 6, 1> xi;
  xi << 0.3, -0.1, 0.2, 0.05, 0.4, -0.02;
  KeyFrameSnapshot kf;
  kf.frame = frame;
  kf.cam_from_world = SE3d::Exp(xi);
  kf.points.assign(frame->size(), kNoId);
  kf.points[0] = 42;
  const dynamic::ReferenceView view = MakeReferenceView(kf);
  EXPECT_EQ(view.points.size(), static_cast<std::size_t>(GridPointsIn(0, 0, 320, 480)));
  EXPECT_EQ(view.points[0].id, 42u);
  EXPECT_EQ(view.points[1].id, kNoId);
  // Back into the keyframe's camera: the keypoint's pixel at 2.5 m.
  const Eigen::Vector3d p_cam = kf.cam_from_world * view.points[1].position_world;
  EXPECT_NEAR(p_cam.z(), 2.5, 1e-9);
  EXPECT_NEAR(kCamera.fx * p_cam.x() / p_cam.z() + kCamera.cx, 48.0, 1e-6);
  EXPECT_NEAR(kCamera.fy * p_cam.y() / p_cam.z() + kCamera.cy, 16.0, 1e-6);
  EXPECT_TRUE(view.cam_from_world.translation().isApprox(kf.cam_from_world.translation()));
}

}  // namespace
}  // namespace dlslam
