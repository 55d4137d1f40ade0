#include "dlslam/features/orientation.h"

#include <opencv2/core/hal/intrin.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numbers>

#include "dlslam/util/check.h"

namespace dlslam::features {

const std::array<int, kPatchRadius + 1>& CirclePatchHalfWidths() {
  static const std::array<int, kPatchRadius + 1> half_widths = [] {
    std::array<int, kPatchRadius + 1> w{};
    constexpr int kRadiusSquared = kPatchRadius * (kPatchRadius + 1);
    for (int v = 0; v <= kPatchRadius; ++v) {
      int u = 0;
      while ((u + 1) * (u + 1) + v * v <= kRadiusSquared) ++u;
      w[static_cast<size_t>(v)] = u;
    }
    return w;
  }();
  return half_widths;
}

namespace {

// Moments over the disc, the plain way (also the reference for the SIMD one).
void ScalarMoments(const uchar* centre, int step, int& m10, int& m01) {
  const auto& half_widths = CirclePatchHalfWidths();
  m10 = 0;
  m01 = 0;
  for (int u = -kPatchRadius; u <= kPatchRadius; ++u) m10 += u * centre[u];
  // Rows +v and -v together: their sum weighs m10, their difference m01.
  for (int v = 1; v <= kPatchRadius; ++v) {
    const uchar* below = centre + v * step;
    const uchar* above = centre - v * step;
    const int w = half_widths[static_cast<size_t>(v)];
    int row_difference = 0;
    for (int u = -w; u <= w; ++u) {
      m10 += u * (below[u] + above[u]);
      row_difference += below[u] - above[u];
    }
    m01 += v * row_difference;
  }
}

#if CV_SIMD128
// Per row offset v, the weights of the 32 pixels u = -16 .. 15 of a row:
// u (for m10) and v (for m01) inside the disc, 0 outside.
struct RowWeights {
  alignas(16) int16_t u[kPatchRadius + 1][32];
  alignas(16) int16_t v[kPatchRadius + 1][32];
};
const RowWeights& MomentWeights() {
  static const RowWeights weights = [] {
    RowWeights w{};
    const auto& half_widths = CirclePatchHalfWidths();
    for (int v = 0; v <= kPatchRadius; ++v) {
      for (int i = 0; i < 32; ++i) {
        const int u = i - 16;
        const bool inside = std::abs(u) <= half_widths[static_cast<size_t>(v)];
        w.u[v][i] = static_cast<int16_t>(inside ? u : 0);
        w.v[v][i] = static_cast<int16_t>(inside ? v : 0);
      }
    }
    return w;
  }();
  return weights;
}

// The same moments 8 pixels at a time; reads centre[-16 .. 15] of each row.
void SimdMoments(const uchar* centre, int step, int& m10, int& m01) {
  const RowWeights& weights = MomentWeights();
  cv::v_int32x4 acc10 = cv::v_setzero_s32(), acc01 = cv::v_setzero_s32();
  const auto load_row = [](const uchar* left, cv::v_int16x8 (&out)[4]) {
    cv::v_uint16x8 a, b, c, d;
    cv::v_expand(cv::v_load(left), a, b);
    cv::v_expand(cv::v_load(left + 16), c, d);
    out[0] = cv::v_reinterpret_as_s16(a);
    out[1] = cv::v_reinterpret_as_s16(b);
    out[2] = cv::v_reinterpret_as_s16(c);
    out[3] = cv::v_reinterpret_as_s16(d);
  };
  cv::v_int16x8 row[4], other[4];
  load_row(centre - 16, row);
  for (int j = 0; j < 4; ++j) {
    acc10 = cv::v_dotprod(row[j], cv::v_load_aligned(weights.u[0] + 8 * j), acc10);
  }
  for (int v = 1; v <= kPatchRadius; ++v) {
    load_row(centre + v * step - 16, row);
    load_row(centre - v * step - 16, other);
    for (int j = 0; j < 4; ++j) {
      // Sums <= 510 and differences in [-255, 255] fit 16 bits.
      acc10 = cv::v_dotprod(row[j] + other[j], cv::v_load_aligned(weights.u[v] + 8 * j), acc10);
      acc01 = cv::v_dotprod(row[j] - other[j], cv::v_load_aligned(weights.v[v] + 8 * j), acc01);
    }
  }
  m10 = cv::v_reduce_sum(acc10);
  m01 = cv::v_reduce_sum(acc01);
}
#endif

}  // namespace

float IntensityCentroidAngle(const cv::Mat& image, int x, int y) {
  DLSLAM_CHECK_EQ(image.type(), CV_8UC1, "orientation needs an 8-bit grey image");
  DLSLAM_CHECK(x >= kPatchRadius && y >= kPatchRadius && x < image.cols - kPatchRadius &&
                   y < image.rows - kPatchRadius,
               "orientation patch at ({}, {}) leaves the {}x{} image", x, y, image.cols,
               image.rows);
  const int step = static_cast<int>(image.step1());
  const uchar* centre = image.ptr<uchar>(y) + x;
  int m10 = 0, m01 = 0;
#if CV_SIMD128
  if (x >= kPatchRadius + 1) {  // the SIMD rows start one pixel further left
    SimdMoments(centre, step, m10, m01);
  } else {
    ScalarMoments(centre, step, m10, m01);
  }
#else
  ScalarMoments(centre, step, m10, m01);
#endif
  float angle = static_cast<float>(std::atan2(static_cast<double>(m01), static_cast<double>(m10)) *
                                    (180.0 / std::numbers::pi));
  if (angle < 0.0f) angle += 360.0f;
  if (angle >= 360.0f) angle -= 360.0f;
  return angle;
}

}  // namespace dlslam::features
