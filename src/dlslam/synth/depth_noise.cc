#include "dlslam/synth/depth_noise.h"

#include <opencv2/imgproc.hpp>

#include <cmath>

#include "dlslam/synth/random.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

void DepthNoiseOptions::Check() const {
  DLSLAM_CHECK(min_range_m >= 0 && min_range_m < max_range_m, "depth range [{}, {}] m is empty", min_range_m,
               max_range_m);
  DLSLAM_CHECK_GE(sigma_base_m, 0.0, "depth noise sigma base [m]");
  DLSLAM_CHECK_GE(sigma_quadratic, 0.0, "depth noise quadratic term [1/m]");
  DLSLAM_CHECK_GT(focal_px, 0.0, "sensor focal length [px]");
  DLSLAM_CHECK_GT(baseline_m, 0.0, "sensor baseline [m]");
  DLSLAM_CHECK_GE(disparity_step_px, 0.0, "disparity step [px]");
  DLSLAM_CHECK(edge_dropout_probability >= 0 && edge_dropout_probability <= 1, "edge dropout probability {}",
               edge_dropout_probability);
  DLSLAM_CHECK(pixel_dropout_probability >= 0 && pixel_dropout_probability <= 1, "pixel dropout probability {}",
               pixel_dropout_probability);
  DLSLAM_CHECK_GE(dropout_blobs, 0, "dropout blobs per frame");
}

double DepthSigma(double z, const DepthNoiseOptions& o) {
  const double d = z - 0.4;
  return o.sigma_base_m + o.sigma_quadratic * d * d;
}

double QuantiseDepth(double z, const DepthNoiseOptions& o) {
  if (o.disparity_step_px <= 0 || z <= 0) return z;
  const double fb = o.focal_px * o.baseline_m;
  const double disparity = std::round(fb / z / o.disparity_step_px) * o.disparity_step_px;
  return disparity > 0 ? fb / disparity : 0.0;
}

cv::Mat ApplyDepthNoise(const cv::Mat& true_depth, const DepthNoiseOptions& o, std::mt19937& rng) {
  DLSLAM_CHECK_EQ(true_depth.type(), CV_32FC1, "true depth must be float metres");
  o.Check();
  cv::Mat out = true_depth.clone();
  if (!o.enabled) return out;
  const int w = out.cols, h = out.rows;
  cv::Mat hole(h, w, CV_8U, cv::Scalar(0));
  const double fb = o.focal_px * o.baseline_m;
  auto is_jump = [&](float near_z, float far_z) {
    return near_z > 0 && (far_z <= 0 || far_z - near_z > o.edge_jump_relative * near_z + o.edge_jump_m);
  };
  // Threshold for 32-bit random numbers.
  const auto edge_cut = static_cast<std::uint32_t>(o.edge_dropout_probability * 4294967295.0);
  for (int y = 0; y < h; ++y) {
    const float* z = true_depth.ptr<float>(y);
    const float* up = true_depth.ptr<float>(std::max(0, y - 1));
    const float* down = true_depth.ptr<float>(std::min(h - 1, y + 1));
    unsigned char* hr = hole.ptr<unsigned char>(y);
    for (int x = 0; x < w; ++x) {
      const float zc = z[x];
      if (zc < o.min_range_m || zc > o.max_range_m) {
        hr[x] = 1;
        continue;
      }
      // The far side of a discontinuity is unreliable (mixed pixels).
      const bool edge = is_jump(z[std::max(0, x - 1)], zc) || is_jump(z[std::min(w - 1, x + 1)], zc) ||
                        is_jump(up[x], zc) || is_jump(down[x], zc);
      if (edge && rng() <= edge_cut) hr[x] = 1;
      // The projector, offset by the baseline, cannot light the background
      // just left of a foreground edge: a band as wide as the disparity step.
      if (o.projector_shadow && x > 0 && is_jump(zc, z[x - 1])) {
        const double far_z = z[x - 1] > 0 ? z[x - 1] : o.max_range_m * 4;
        const int band = static_cast<int>(std::lround(fb * (1.0 / zc - 1.0 / far_z)));
        for (int k = 1; k <= band && x - k >= 0 && z[x - k] > zc; ++k) hr[x - k] = 1;
      }
    }
  }
  // Isolated dropouts: their expected number at random places (cheaper than a draw per pixel).
  const int isolated = static_cast<int>(o.pixel_dropout_probability * w * h + Uniform01(rng));
  for (int k = 0; k < isolated; ++k) hole.at<unsigned char>(UniformInt(rng, 0, h - 1), UniformInt(rng, 0, w - 1)) = 1;
  for (int b = 0; b < o.dropout_blobs; ++b) {
    const cv::Point c(UniformInt(rng, 0, w - 1), UniformInt(rng, 0, h - 1));
    const cv::Size axes(static_cast<int>(Uniform(rng, 1, o.max_blob_radius_px)),
                        static_cast<int>(Uniform(rng, 1, o.max_blob_radius_px)));
    cv::ellipse(hole, c, axes, Uniform(rng, 0, 180), 0, 360, cv::Scalar(1), cv::FILLED);
  }
  const float* normal = StandardNormalTable();
  std::uint32_t bits = 0;
  bool have_half = false;
  for (int y = 0; y < h; ++y) {
    float* z = out.ptr<float>(y);
    const unsigned char* hr = hole.ptr<unsigned char>(y);
    for (int x = 0; x < w; ++x) {
      if (hr[x]) {
        z[x] = 0.0f;
        continue;
      }
      // Two 16-bit normal samples per 32-bit draw.
      if (!have_half) bits = rng();
      const float n = normal[have_half ? (bits >> 16) : (bits & 0xFFFFu)];
      have_half = !have_half;
      const double noisy = z[x] + DepthSigma(z[x], o) * n;
      z[x] = static_cast<float>(QuantiseDepth(noisy, o));
    }
  }
  return out;
}

}  // namespace dlslam::synth
