#include "dlslam/data/frame.h"

#include <gtest/gtest.h>

#include <cstring>

#include <random>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

struct Input {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  cv::Mat depth;
};

Input RandomInput(int n, unsigned seed) {
  Input in;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> ux(0, 639), uy(0, 479);
  for (int i = 0; i < n; ++i) {
    cv::KeyPoint k(ux(rng), uy(rng), 31.f, 0.f, 1.f, i % 8);
    in.keypoints.push_back(k);
  }
  in.descriptors = cv::Mat(n, 32, CV_8UC1, cv::Scalar(0));
  in.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  in.depth(cv::Rect(0, 0, 320, 480)).setTo(0.0f);  // left half without depth
  return in;
}

TEST(Frame, DepthAndRightCoordinate) {
  const CameraIntrinsics cam = CameraPreset("freiburg3");
  const Input in = RandomInput(200, 1);
  const Frame f = Frame::Create(1.0, in.keypoints, in.descriptors, in.depth, cam, ScalePyramid());
  ASSERT_EQ(f.size(), 200u);
  for (std::size_t i = 0; i < f.size(); ++i) {
    const auto& k = f.keypoint(i);
    if (std::lround(in.keypoints[i].pt.x) < 320) {
      EXPECT_EQ(k.depth, 0.0);
      EXPECT_LT(k.right_u, 0.0);
      EXPECT_FALSE(f.Unproject(i).has_value());
    } else {
      EXPECT_DOUBLE_EQ(k.depth, 2.0);
      EXPECT_DOUBLE_EQ(k.right_u, k.uv.x() - cam.bf / 2.0);
      const Eigen::Vector3d p = *f.Unproject(i);
      EXPECT_LT((cam.Project(p) - k.uv).norm(), 1e-9);
    }
  }
}

TEST(Frame, FeaturesInAreaMatchesBruteForce) {
  const Input in = RandomInput(1000, 2);
  const Frame f = Frame::Create(0, in.keypoints, in.descriptors, in.depth, CameraPreset("fr1"), ScalePyramid());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(-20, 660), uy(-20, 500), ur(1, 60);
  for (int q = 0; q < 200; ++q) {
    const double u = ux(rng), v = uy(rng), r = ur(rng);
    std::vector<int> got = f.FeaturesInArea(u, v, r, 1, 5);
    std::sort(got.begin(), got.end());
    std::vector<int> expected;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const auto& k = f.keypoint(i);
      if (k.octave >= 1 && k.octave <= 5 && (k.uv - Eigen::Vector2d(u, v)).norm() <= r) {
        expected.push_back(static_cast<int>(i));
      }
    }
    EXPECT_EQ(got, expected);
  }
}

TEST(Frame, DistortedKeypointsAreUndistorted) {
  const CameraIntrinsics cam = CameraPreset("freiburg1");
  const Eigen::Vector2d undistorted(100.0, 80.0);
  const Eigen::Vector2d xn((undistorted.x() - cam.cx) / cam.fx, (undistorted.y() - cam.cy) / cam.fy);
  const Eigen::Vector2d d = cam.Distort(xn);
  const cv::KeyPoint k(static_cast<float>(d.x() * cam.fx + cam.cx), static_cast<float>(d.y() * cam.fy + cam.cy), 31.f);
  const Frame f = Frame::Create(0, {k}, cv::Mat(1, 32, CV_8UC1, cv::Scalar(0)), cv::Mat(), cam, ScalePyramid());
  EXPECT_LT((f.keypoint(0).uv - undistorted).norm(), 0.05);
}

TEST(Frame, WithoutMaskedKeepsOnlyTheKeypointsOffTheMask) {
  const Input in = RandomInput(500, 4);
  const Frame f = Frame::Create(0, in.keypoints, in.descriptors, in.depth, CameraPreset("fr3"), ScalePyramid());
  cv::Mat mask(480, 640, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(100, 100, 200, 200)).setTo(255);
  const std::vector<bool> on = f.OnMask(mask);
  ASSERT_EQ(on.size(), f.size());
  std::vector<std::size_t> outside;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const auto& p = in.keypoints[i].pt;
    const bool inside = std::lround(p.x) >= 100 && std::lround(p.x) < 300 && std::lround(p.y) >= 100 &&
                        std::lround(p.y) < 300;
    EXPECT_EQ(on[i], inside);
    if (!inside) outside.push_back(i);
  }
  ASSERT_GT(outside.size(), 0u);
  ASSERT_LT(outside.size(), f.size());
  const Frame statics = f.WithoutMasked(mask);
  ASSERT_EQ(statics.size(), outside.size());
  // The same keypoints, descriptors and depth, in the same order.
  for (std::size_t j = 0; j < outside.size(); ++j) {
    const std::size_t i = outside[j];
    EXPECT_EQ(statics.keypoint(j).uv, f.keypoint(i).uv);
    EXPECT_EQ(statics.keypoint(j).depth, f.keypoint(i).depth);
    EXPECT_EQ(0, std::memcmp(statics.descriptor(j), f.descriptor(i), 32));
  }
  EXPECT_TRUE(statics.FeaturesInArea(200, 200, 50).empty());
  EXPECT_FALSE(f.FeaturesInArea(200, 200, 50).empty());
  EXPECT_EQ(statics.timestamp(), f.timestamp());
  EXPECT_THROW(f.OnMask(cv::Mat(480, 640, CV_32FC1)), Error);
  EXPECT_THROW(f.Subset(std::vector<bool>(3, true)), Error);
  EXPECT_EQ(f.Subset(std::vector<bool>(f.size(), false)).size(), 0u);
}

TEST(Frame, RejectsInconsistentInput) {
  const Input in = RandomInput(10, 5);
  EXPECT_THROW(Frame::Create(0, in.keypoints, cv::Mat(9, 32, CV_8UC1), in.depth, CameraPreset("fr3"), ScalePyramid()),
               Error);
  cv::Mat depth16(480, 640, CV_16UC1);
  EXPECT_THROW(Frame::Create(0, in.keypoints, in.descriptors, depth16, CameraPreset("fr3"), ScalePyramid()), Error);
}

}  // namespace
}  // namespace dlslam
