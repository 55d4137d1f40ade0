#include "dlslam/features/brief_descriptor.h"

#include <opencv2/core/hal/intrin.hpp>

#include <cmath>
#include <numbers>

#include "dlslam/util/check.h"

namespace dlslam::features {
TestRotation::TestRotation(float angle_deg) {
  const float radians = angle_deg * static_cast<float>(std::numbers::pi / 180.0);
  cos_a = std::cos(radians);
  sin_a = std::sin(radians);
}

cv::Point RotateTestPoint(float x, float y, const TestRotation& r) {
  const float rx = x * r.cos_a - y * r.sin_a;
  const float ry = x * r.sin_a + y * r.cos_a;
  return {static_cast<int>(std::nearbyint(rx)), static_cast<int>(std::nearbyint(ry))};
}

SteeredBrief::SteeredBrief(std::span<const PatternTest> pattern) {
  DLSLAM_CHECK_EQ(pattern.size(), static_cast<size_t>(kPatternTests), "BRIEF pattern size");
  for (size_t i = 0; i < pattern.size(); ++i) {
    const PatternTest& t = pattern[i];
    for (const auto& [px, py] : {std::pair{t.x1, t.y1}, std::pair{t.x2, t.y2}}) {
      DLSLAM_CHECK(px * px + py * py <= kPatchRadius * kPatchRadius,
                   "BRIEF test {} point ({}, {}) outside the patch disc of radius {}", i, px, py,
                   kPatchRadius);
    }
    x_[2 * i] = t.x1;
    y_[2 * i] = t.y1;
    x_[2 * i + 1] = t.x2;
    y_[2 * i + 1] = t.y2;
  }
}

cv::Point SteeredBrief::RotatedPoint(int point, float angle_deg) const {
  DLSLAM_CHECK(point >= 0 && point < kPoints, "BRIEF point index {}", point);
  return RotateTestPoint(x_[static_cast<size_t>(point)], y_[static_cast<size_t>(point)],
                         TestRotation(angle_deg));
}

void SteeredBrief::Compute(const cv::Mat& smoothed, int x, int y, float angle_deg,
                           uchar* out) const {
  DLSLAM_CHECK(smoothed.type() == CV_8UC1 && x >= kPatchRadius && y >= kPatchRadius &&
                   x < smoothed.cols - kPatchRadius && y < smoothed.rows - kPatchRadius,
               "BRIEF patch at ({}, {}) leaves the {}x{} image (type {})", x, y, smoothed.cols,
               smoothed.rows, smoothed.type());
  const TestRotation rotation(angle_deg);
  const int step = static_cast<int>(smoothed.step1());
  alignas(16) int offsets[kPoints];
  int i = 0;
#if CV_SIMD128
  const cv::v_float32x4 vc = cv::v_setall_f32(rotation.cos_a);
  const cv::v_float32x4 vs = cv::v_setall_f32(rotation.sin_a);
  const cv::v_int32x4 vstep = cv::v_setall_s32(step);
  for (; i < kPoints; i += 4) {
    const cv::v_float32x4 px = cv::v_load_aligned(x_.data() + i);
    const cv::v_float32x4 py = cv::v_load_aligned(y_.data() + i);
    const cv::v_int32x4 rx = cv::v_round(px * vc - py * vs);
    const cv::v_int32x4 ry = cv::v_round(px * vs + py * vc);
    cv::v_store_aligned(offsets + i, ry * vstep + rx);
  }
#endif
  for (; i < kPoints; ++i) {
    const cv::Point p = RotateTestPoint(x_[static_cast<size_t>(i)], y_[static_cast<size_t>(i)], rotation);
    offsets[i] = p.y * step + p.x;
  }
  const uchar* centre = smoothed.ptr<uchar>(y) + x;
  const int* o = offsets;
  for (int byte = 0; byte < kDescriptorBytes; ++byte, o += 16) {
    unsigned bits = 0;
    for (int bit = 0; bit < 8; ++bit) {
      bits |= static_cast<unsigned>(centre[o[2 * bit]] < centre[o[2 * bit + 1]]) << bit;
    }
    out[byte] = static_cast<uchar>(bits);
  }
}

}  // namespace dlslam::features
