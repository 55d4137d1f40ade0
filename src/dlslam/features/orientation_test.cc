#include "dlslam/features/orientation.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>

#include "dlslam/features/test_images.h"
#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

double AngleDifference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

TEST(CirclePatchTest, DiscIsSymmetricUnderTransposition) {
  const auto& w = CirclePatchHalfWidths();
  EXPECT_EQ(w[0], kPatchRadius);
  for (int v = 0; v <= kPatchRadius; ++v) {
    for (int u = 0; u <= kPatchRadius; ++u) {
      const bool inside = u <= w[static_cast<size_t>(v)];
      const bool transposed_inside = v <= w[static_cast<size_t>(u)];
      EXPECT_EQ(inside, transposed_inside) << u << "," << v;
    }
  }
}

TEST(IntensityCentroidAngleTest, PointsUpTheIntensityRamp) {
  for (double theta : {0.0, 30.0, 45.0, 90.0, 135.0, 200.0, 271.0, 330.0}) {
    const double c = std::cos(theta * std::numbers::pi / 180), s = std::sin(theta * std::numbers::pi / 180);
    cv::Mat image(64, 64, CV_8UC1);
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        image.at<uchar>(y, x) = cv::saturate_cast<uchar>(128 + 3.5 * ((x - 32) * c + (y - 32) * s));
      }
    }
    EXPECT_LT(AngleDifference(IntensityCentroidAngle(image, 32, 32), theta), 1.0) << theta;
  }
}

TEST(IntensityCentroidAngleTest, PointsAtAnOffCentreBlob) {
  for (double theta : {10.0, 100.0, 190.0, 280.0}) {
    cv::Mat image(64, 64, CV_8UC1, cv::Scalar(20));
    const cv::Point2d blob(32 + 8 * std::cos(theta * std::numbers::pi / 180),
                           32 + 8 * std::sin(theta * std::numbers::pi / 180));
    cv::circle(image, cv::Point(cvRound(blob.x * 16), cvRound(blob.y * 16)), 5 * 16,
               cv::Scalar(230), cv::FILLED, cv::LINE_AA, 4);
    cv::GaussianBlur(image, image, cv::Size(5, 5), 1.0);
    const float angle = IntensityCentroidAngle(image, 32, 32);
    EXPECT_LT(AngleDifference(angle, theta), 2.0) << theta;
    EXPECT_GE(angle, 0.0f);
    EXPECT_LT(angle, 360.0f);
  }
}

TEST(IntensityCentroidAngleTest, MatchesMomentsSummedOverTheDisc) {
  const cv::Mat image = testing::SyntheticTexture(120, 90, 9);
  const auto& w = CirclePatchHalfWidths();
  // x = 15 and 16 take the scalar and the vector paths.
  for (const cv::Point& p : {cv::Point(15, 15), cv::Point(16, 40), cv::Point(60, 45),
                             cv::Point(104, 74), cv::Point(77, 20)}) {
    double m10 = 0, m01 = 0;
    for (int v = -kPatchRadius; v <= kPatchRadius; ++v) {
      for (int u = -w[static_cast<size_t>(std::abs(v))]; u <= w[static_cast<size_t>(std::abs(v))]; ++u) {
        m10 += u * image.at<uchar>(p.y + v, p.x + u);
        m01 += v * image.at<uchar>(p.y + v, p.x + u);
      }
    }
    double expected = std::atan2(m01, m10) * 180 / std::numbers::pi;
    if (expected < 0) expected += 360;
    EXPECT_NEAR(IntensityCentroidAngle(image, p.x, p.y), expected, 1e-3) << p;
  }
}

TEST(IntensityCentroidAngleTest, RejectsPatchesLeavingTheImage) {
  const cv::Mat image = testing::SyntheticTexture(64, 64);
  EXPECT_THROW(IntensityCentroidAngle(image, 14, 32), Error);
  EXPECT_THROW(IntensityCentroidAngle(image, 32, 49), Error);
  EXPECT_THROW(IntensityCentroidAngle(cv::Mat(64, 64, CV_8UC3), 32, 32), Error);
}

}  // namespace
}  // namespace dlslam::features
