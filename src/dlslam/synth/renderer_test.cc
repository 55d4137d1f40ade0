#include "dlslam/synth/renderer.h"

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <vector>

#include "dlslam/synth/room.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {
namespace {

bool Same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

SynthOptions Options(Preset preset, std::uint32_t seed, int frames = 240) {
  SynthOptions o;
  o.preset = preset;
  o.seed = seed;
  o.frames = frames;
  return o;
}

TEST(Renderer, SameSeedSameFrameDifferentSeedDifferentFrame) {
  const SynthSequence a(Options(Preset::kWalkingXyz, 5, 10)), b(Options(Preset::kWalkingXyz, 5, 10));
  const SynthSequence c(Options(Preset::kWalkingXyz, 6, 10));
  const RenderedFrame fa = a.Render(7), fb = b.Render(7), fa_again = a.Render(7), fc = c.Render(7);
  EXPECT_TRUE(Same(fa.colour, fb.colour));
  EXPECT_TRUE(Same(fa.depth, fb.depth));
  EXPECT_TRUE(Same(fa.mask, fb.mask));
  EXPECT_TRUE(Same(fa.colour, fa_again.colour)) << "rendering has no hidden state";
  EXPECT_TRUE(Same(fa.depth, fa_again.depth));
  cv::Mat diff;
  cv::absdiff(fa.colour, fc.colour, diff);
  EXPECT_GT(cv::countNonZero(diff.reshape(1) > 20), 50000) << "another seed, another room";
  // Consecutive frames differ in their noise even where nothing moves.
  const RenderedFrame f8 = a.Render(8);
  EXPECT_FALSE(Same(fa.depth, f8.depth));
}

TEST(Renderer, FrameLayout) {
  const SynthSequence s(Options(Preset::kWalkingXyz, 1, 3));
  const RenderedFrame f = s.Render(2);
  EXPECT_EQ(f.colour.type(), CV_8UC3);
  EXPECT_EQ(f.depth.type(), CV_32FC1);
  EXPECT_EQ(f.true_depth.type(), CV_32FC1);
  EXPECT_EQ(f.mask.type(), CV_8UC1);
  EXPECT_EQ(f.colour.size(), cv::Size(640, 480));
  EXPECT_EQ(cv::countNonZero(f.true_depth > 0), 640 * 480) << "the room is closed";
  EXPECT_NEAR(f.scene_time, 2 / 30.0, 1e-6);
  EXPECT_THROW(s.Render(3), Error);
  EXPECT_THROW(s.Render(-1), Error);
}

// Known static points of the room, seen along a moving camera path: the
// depth at their pixel, unprojected with the ground-truth pose, lands on
// their surface (desk top z = 0.75, far wall y = 3.4).
TEST(Renderer, DepthAndPoseAgreeOnKnownStaticPoints) {
  const SynthSequence s(Options(Preset::kStatic, 3, 900));
  const CameraIntrinsics& camera = s.options().camera;
  struct Point {
    Eigen::Vector3d p;
    int axis;  // the surface's normal axis: the plane is p[axis] = const
  };
  const Point points[] = {{{0.2, 1.5, room::kDeskMax.z()}, 2},
                          {{-0.2, 1.45, room::kDeskMax.z()}, 2},
                          {{0.0, room::kMax.y(), 1.9}, 1},
                          {{0.4, room::kMax.y(), 1.4}, 1}};
  int checked = 0;
  for (int i = 0; i < s.size(); i += 150) {
    const RenderedFrame f = s.Render(i);
    const SE3d cam_from_world = f.world_from_cam.Inverse();
    for (const Point& point : points) {
      const Eigen::Vector3d pc = cam_from_world * point.p;
      const Eigen::Vector2d uv = camera.Project(pc);
      const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
      if (pc.z() <= 0 || u < 2 || v < 2 || u >= camera.width - 2 || v >= camera.height - 2) continue;
      const double z = f.true_depth.at<float>(v, u);
      const Eigen::Vector3d back = f.world_from_cam * camera.Unproject(Eigen::Vector2d(u, v), z);
      EXPECT_NEAR(back[point.axis], point.p[point.axis], 0.003) << "frame " << i << " point " << point.p.transpose();
      EXPECT_LT((back - point.p).norm(), 0.015) << "frame " << i << " point " << point.p.transpose();
      EXPECT_EQ(f.mask.at<std::uint8_t>(v, u), 0);
      // The sensor's depth around it: unbiased within its noise and quantisation.
      std::vector<float> measured;
      for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
          if (const float m = f.depth.at<float>(v + dy, u + dx); m > 0) measured.push_back(m);
        }
      }
      ASSERT_GE(measured.size(), 10u);
      std::nth_element(measured.begin(), measured.begin() + measured.size() / 2, measured.end());
      const double step = z * z / (8 * 580.0 * 0.075);
      EXPECT_NEAR(measured[measured.size() / 2], z, 3 * DepthSigma(z, {}) + step) << "frame " << i;
      ++checked;
    }
  }
  EXPECT_GE(checked, 16);
}

// ORB-SLAM needs many, well spread corners: at least 500 ORB keypoints, in
// at least 12 of the 16 cells of a 4x4 grid.
TEST(Renderer, TypicalFramesAreRichInOrbFeatures) {
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(2000);
  for (const Preset preset : {Preset::kWalkingXyz, Preset::kWalkingRpy, Preset::kSittingStatic}) {
    const SynthSequence s(Options(preset, 8, 600));
    for (const int i : {0, 200, 450}) {
      cv::Mat grey;
      cv::cvtColor(s.Render(i).colour, grey, cv::COLOR_BGR2GRAY);
      std::vector<cv::KeyPoint> keypoints;
      orb->detect(grey, keypoints);
      int cells[16] = {};
      for (const auto& k : keypoints) ++cells[static_cast<int>(k.pt.y / 120) * 4 + static_cast<int>(k.pt.x / 160)];
      const auto covered = std::count_if(std::begin(cells), std::end(cells), [](int n) { return n >= 5; });
      EXPECT_GE(keypoints.size(), 500u) << PresetName(preset) << " frame " << i;
      EXPECT_GE(covered, 12) << PresetName(preset) << " frame " << i;
    }
  }
}

// The texture is distinct, not repetitive: ORB matches between two frames
// a sixth of a second apart are mostly where the ground truth (true depth and
// poses) puts them. The room only (the people may cover much of a frame).
TEST(Renderer, OrbMatchesAgreeWithTheGroundTruth) {
  const SynthSequence s(Options(Preset::kWalkingHalfsphere, 8, 120));
  const CameraIntrinsics& camera = s.options().camera;
  Scene room = s.scene();
  room.actors.clear();
  auto render = [&](int i) {
    std::mt19937 rng(static_cast<unsigned>(i));
    const StampedPose& p = s.camera_path()[static_cast<std::size_t>(i)];
    return RenderFrame(room, camera, {p.world_from_cam(), p.timestamp - s.camera_path()[0].timestamp},
                       s.options().render, rng);
  };
  const RenderedFrame a = render(100), b = render(105);
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  std::vector<cv::KeyPoint> ka, kb;
  cv::Mat da, db, grey_a, grey_b;
  cv::cvtColor(a.colour, grey_a, cv::COLOR_BGR2GRAY);
  cv::cvtColor(b.colour, grey_b, cv::COLOR_BGR2GRAY);
  orb->detectAndCompute(grey_a, cv::noArray(), ka, da);
  orb->detectAndCompute(grey_b, cv::noArray(), kb, db);
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(da, db, knn, 2);
  const SE3d b_from_a = b.world_from_cam.Inverse() * a.world_from_cam;
  int tested = 0, correct = 0;
  for (const auto& m : knn) {
    if (m.size() < 2 || m[0].distance > 0.8 * m[1].distance) continue;  // Lowe's ratio test
    const cv::Point2f pa = ka[static_cast<std::size_t>(m[0].queryIdx)].pt;
    const cv::Point2f pb = kb[static_cast<std::size_t>(m[0].trainIdx)].pt;
    const int u = static_cast<int>(std::lround(pa.x)), v = static_cast<int>(std::lround(pa.y));
    if (a.mask.at<std::uint8_t>(v, u) != 0) continue;  // static world only
    const Eigen::Vector3d in_b = b_from_a * camera.Unproject(Eigen::Vector2d(pa.x, pa.y), a.true_depth.at<float>(v, u));
    const Eigen::Vector2d predicted = camera.Project(in_b);
    ++tested;
    correct += (predicted - Eigen::Vector2d(pb.x, pb.y)).norm() < 4.0;
  }
  EXPECT_GE(tested, 200);
  EXPECT_GE(correct, 0.8 * tested);
}

TEST(Renderer, OptionsCheck) {
  RenderOptions o;
  EXPECT_NO_THROW(o.Check());
  o.motion_blur_samples = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.moving_interval_s = 0;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.colour_noise_sigma = -1;
  EXPECT_THROW(o.Check(), Error);
}

TEST(Renderer, MotionBlurSmearsOnlyWhenAsked) {
  SynthOptions options = Options(Preset::kWalkingRpy, 2, 200);
  options.render.colour_noise_sigma = 0;
  options.render.depth.enabled = false;
  const SynthSequence sharp(options);
  options.render.motion_blur_samples = 4;
  options.render.exposure_s = 0.03;
  const SynthSequence blurred(options);
  // Frame 120 (4 s): the camera rotates fast. Blur lowers the image's high frequencies.
  auto sharpness = [](const cv::Mat& bgr) {
    cv::Mat grey, lap;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    cv::Laplacian(grey, lap, CV_32F);
    return cv::norm(lap);
  };
  const RenderedFrame a = sharp.Render(120), b = blurred.Render(120);
  EXPECT_LT(sharpness(b.colour), 0.9 * sharpness(a.colour));
  EXPECT_TRUE(Same(a.true_depth, b.true_depth)) << "ground truth is the frame's instant";
}

}  // namespace
}  // namespace dlslam::synth
