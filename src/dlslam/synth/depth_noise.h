#pragma once
// A Kinect-v1-like depth sensor applied to a perfect depth map: holes where
// the structured light fails (out of range, depth discontinuities, the
// projector's shadow beside foreground objects, random dropouts), Gaussian
// noise whose sigma grows with depth squared (Nguyen, Izadi, Lovell 2012:
// sigma_z = 0.0012 + 0.0019 (z - 0.4)^2 m) and the quantisation of a
// 1/8-pixel disparity (depth step ~ z^2 / (8 f b)).

#include <opencv2/core.hpp>

#include <random>

namespace dlslam::synth {

struct DepthNoiseOptions {
  bool enabled = true;              // false: return the true depth unchanged
  double min_range_m = 0.4;         // nearer is a hole [m]
  double max_range_m = 4.0;         // farther is a hole [m]
  double sigma_base_m = 0.0012;     // noise sigma at min_range_m [m]
  double sigma_quadratic = 0.0019;  // [1/m]: sigma = base + quadratic * (z - 0.4)^2
  double focal_px = 580.0;          // of the IR camera [px] (quantisation and shadows)
  double baseline_m = 0.075;        // projector to IR camera [m]
  double disparity_step_px = 0.125; // quantisation of the disparity [px]; 0 = off
  double edge_jump_relative = 0.05; // a neighbour this much farther (fraction of z) ...
  double edge_jump_m = 0.02;        // ... plus this [m] is a depth discontinuity
  double edge_dropout_probability = 0.6;   // of each pixel beside a discontinuity
  bool projector_shadow = true;            // holes left of foreground edges
  double pixel_dropout_probability = 0.002;  // isolated missing pixels
  int dropout_blobs = 6;            // small missing patches per frame
  double max_blob_radius_px = 4.0;

  // Throws dlslam::Error naming the offending value.
  void Check() const;
};

// Noise sigma [m] of a measurement at true depth z [m].
double DepthSigma(double z, const DepthNoiseOptions& options);

// The depth the sensor reports for z [m] after disparity quantisation.
double QuantiseDepth(double z, const DepthNoiseOptions& options);

// The sensor's view of `true_depth` (CV_32F metres, 0 = nothing): CV_32F
// metres with 0 for holes. Deterministic in the state of `rng`.
cv::Mat ApplyDepthNoise(const cv::Mat& true_depth, const DepthNoiseOptions& options, std::mt19937& rng);

}  // namespace dlslam::synth
