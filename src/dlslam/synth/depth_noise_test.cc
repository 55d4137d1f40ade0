#include "dlslam/synth/depth_noise.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::synth {
namespace {

// Mean and standard deviation of the non-zero pixels; `valid` counts them.
void Stats(const cv::Mat& depth, double& mean, double& stddev, int& valid) {
  double sum = 0, sum_sq = 0;
  valid = 0;
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      const double z = depth.at<float>(y, x);
      if (z <= 0) continue;
      sum += z;
      sum_sq += z * z;
      ++valid;
    }
  }
  mean = sum / valid;
  stddev = std::sqrt(sum_sq / valid - mean * mean);
}

DepthNoiseOptions NoiseOnly() {
  DepthNoiseOptions o;
  o.disparity_step_px = 0;
  o.pixel_dropout_probability = 0;
  o.dropout_blobs = 0;
  return o;
}

TEST(DepthNoise, FlatWallMatchesTheNoiseModel) {
  // sigma = 0.0012 + 0.0019 (z - 0.4)^2 (Nguyen et al. 2012), written out here.
  for (const double z : {0.8, 2.0, 3.5}) {
    const cv::Mat wall(480, 640, CV_32FC1, cv::Scalar(z));
    std::mt19937 rng(7);
    const cv::Mat noisy = ApplyDepthNoise(wall, NoiseOnly(), rng);
    double mean = 0, stddev = 0;
    int valid = 0;
    Stats(noisy, mean, stddev, valid);
    const double sigma = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
    EXPECT_EQ(valid, 640 * 480) << "no holes on a flat wall in range";
    EXPECT_NEAR(mean, z, 4 * sigma / std::sqrt(valid) + 1e-5) << "z " << z;
    EXPECT_NEAR(stddev, sigma, 0.02 * sigma) << "z " << z;
  }
}

TEST(DepthNoise, DisparityQuantisationStepGrowsWithDepthSquared) {
  DepthNoiseOptions o;
  const double fb = 580.0 * 0.075;
  for (double z = 0.5; z < 4.0; z += 0.137) {
    const double q = QuantiseDepth(z, o);
    // Half a 1/8-px disparity step, in depth: z^2 / (2 * 8 * f * b).
    EXPECT_LE(std::abs(q - z), z * z / (16 * fb) * 1.01) << z;
    const double disparity_eighths = fb / q * 8;
    EXPECT_NEAR(disparity_eighths, std::round(disparity_eighths), 1e-6) << z;
  }
  // Quantised wall: on the lattice, unbiased, spread of noise plus rounding.
  const double z = 2.5;
  const cv::Mat wall(480, 640, CV_32FC1, cv::Scalar(z));
  DepthNoiseOptions q = NoiseOnly();
  q.disparity_step_px = 0.125;
  std::mt19937 rng(3);
  const cv::Mat noisy = ApplyDepthNoise(wall, q, rng);
  double mean = 0, stddev = 0;
  int valid = 0;
  Stats(noisy, mean, stddev, valid);
  const double step = z * z / (8 * fb);
  const double sigma = DepthSigma(z, q);
  EXPECT_NEAR(mean, z, 0.1 * step);
  EXPECT_NEAR(stddev, std::sqrt(sigma * sigma + step * step / 12), 0.1 * sigma);
}

TEST(DepthNoise, HolesOutOfRangeAndInTheProjectorShadow) {
  DepthNoiseOptions o = NoiseOnly();
  o.edge_dropout_probability = 0;
  std::mt19937 rng(1);
  EXPECT_EQ(cv::countNonZero(ApplyDepthNoise(cv::Mat(48, 64, CV_32FC1, cv::Scalar(0.3)), o, rng)), 0);
  EXPECT_EQ(cv::countNonZero(ApplyDepthNoise(cv::Mat(48, 64, CV_32FC1, cv::Scalar(4.5)), o, rng)), 0);
  // Background at 3 m, foreground at 1.5 m from column 320 on: the shadow left
  // of the edge is f b (1/1.5 - 1/3) = 14.5 px wide.
  cv::Mat scene(480, 640, CV_32FC1, cv::Scalar(3.0));
  scene.colRange(320, 640).setTo(1.5);
  const cv::Mat noisy = ApplyDepthNoise(scene, o, rng);
  EXPECT_EQ(cv::countNonZero(noisy.colRange(307, 320)), 0) << "shadow band";
  EXPECT_EQ(cv::countNonZero(noisy.colRange(0, 300)), 300 * 480) << "lit background";
  EXPECT_EQ(cv::countNonZero(noisy.colRange(320, 640)), 320 * 480) << "foreground";
}

TEST(DepthNoise, DropoutsAtDiscontinuitiesAndRandom) {
  cv::Mat scene(480, 640, CV_32FC1, cv::Scalar(3.0));
  scene(cv::Rect(200, 100, 200, 200)).setTo(1.0);
  DepthNoiseOptions o;
  o.projector_shadow = false;
  std::mt19937 rng(5);
  const cv::Mat noisy = ApplyDepthNoise(scene, o, rng);
  // The background ring around the square loses about edge_dropout_probability of its pixels.
  const int ring = 2 * 202 + 2 * 200;
  const cv::Rect outer(199, 99, 202, 202);
  const int ring_valid = cv::countNonZero(noisy(outer)) - cv::countNonZero(noisy(cv::Rect(200, 100, 200, 200)));
  EXPECT_NEAR(1.0 - static_cast<double>(ring_valid) / ring, o.edge_dropout_probability, 0.1);
  // Elsewhere: only the sparse random dropouts.
  const double hole_fraction = 1.0 - cv::countNonZero(noisy.colRange(450, 640)) / (190.0 * 480);
  EXPECT_GT(hole_fraction, 0.0);
  EXPECT_LT(hole_fraction, 0.01);
}

TEST(DepthNoise, DeterministicInTheEngine) {
  const cv::Mat wall(120, 160, CV_32FC1, cv::Scalar(2.0));
  std::mt19937 a(11), b(11), c(12);
  const DepthNoiseOptions o;
  const cv::Mat da = ApplyDepthNoise(wall, o, a), db = ApplyDepthNoise(wall, o, b), dc = ApplyDepthNoise(wall, o, c);
  EXPECT_EQ(cv::countNonZero(da != db), 0);
  EXPECT_GT(cv::countNonZero(da != dc), 1000);
}

TEST(DepthNoise, DisabledReturnsTheTruth) {
  cv::Mat scene(48, 64, CV_32FC1, cv::Scalar(2.0));
  scene.colRange(10, 20).setTo(0.2);
  DepthNoiseOptions o;
  o.enabled = false;
  std::mt19937 rng(1);
  EXPECT_EQ(cv::countNonZero(ApplyDepthNoise(scene, o, rng) != scene), 0);
}

TEST(DepthNoise, OptionsCheckNamesTheBadValue) {
  DepthNoiseOptions o;
  o.max_range_m = 0.2;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.edge_dropout_probability = 1.5;
  EXPECT_THROW(o.Check(), Error);
  o = {};
  o.baseline_m = 0;
  EXPECT_THROW(o.Check(), Error);
  EXPECT_NO_THROW(DepthNoiseOptions{}.Check());
}

}  // namespace
}  // namespace dlslam::synth
