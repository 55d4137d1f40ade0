#pragma once
// Steered BRIEF: the binary tests of a pattern, rotated by the keypoint's
// angle, on a smoothed image.

#include <opencv2/core.hpp>

#include <array>
#include <span>

#include "dlslam/features/orb_options.h"
#include "dlslam/features/orb_pattern.h"

namespace dlslam::features {

// cos and sin of an angle in degrees, in float as Compute uses them.
struct TestRotation {
  explicit TestRotation(float angle_deg);
  float cos_a, sin_a;
};
// A test point rotated by `r` and rounded to the nearest pixel (ties to
// even), bit for bit as Compute does it.
cv::Point RotateTestPoint(float x, float y, const TestRotation& r);

class SteeredBrief {
 public:
  // `pattern`: kPatternTests tests inside the disc of radius kPatchRadius.
  // Throws dlslam::Error otherwise.
  explicit SteeredBrief(std::span<const PatternTest> pattern = LearnedOrbPattern());

  // Writes the kDescriptorBytes-byte descriptor of pixel (x, y) of `smoothed`
  // (8-bit grey) with orientation `angle_deg` into `out`. Test i sets bit
  // i % 8 of byte i / 8 when I(R p1) < I(R p2), R the rotation by the angle
  // (x towards y) and the rotated points rounded to the nearest pixel
  // (ties to even). (x, y) must be 15 px or more inside the image.
  void Compute(const cv::Mat& smoothed, int x, int y, float angle_deg, uchar* out) const;

  // The pixel offset (dx, dy) that test point `point` (0..511: test
  // point / 2, first or second point) is read at for an angle, the rounding
  // Compute uses. For learning and testing.
  cv::Point RotatedPoint(int point, float angle_deg) const;

  // The same tests: the same descriptors.
  bool operator==(const SteeredBrief& other) const = default;

 private:
  static constexpr int kPoints = 2 * kPatternTests;
  alignas(16) std::array<float, kPoints> x_{};  // test points, first and second interleaved
  alignas(16) std::array<float, kPoints> y_{};
};

}  // namespace dlslam::features
