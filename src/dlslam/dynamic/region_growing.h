#pragma once
// Grows the dynamic regions of the current frame from seed pixels over the
// depth image: a 4-connected flood fill that crosses from a pixel to its
// neighbour only when their depths are close, so it stops at depth
// discontinuities (the silhouette of a person against the background).

#include <opencv2/core.hpp>

#include <vector>

namespace dlslam::dynamic {

struct RegionGrowingOptions {
  // Neighbours join when |d_a - d_b| <= max_step_m + max_step_relative * d_a
  // [m, 1]: a person's surface changes by millimetres per pixel, a silhouette
  // edge by decimetres.
  double max_step_m = 0.02;
  double max_step_relative = 0.01;
  // A pixel joins only within this depth of its region's seed [m]: stops the
  // fill leaking along surfaces that touch the object (the floor at the
  // feet); about a person's depth extent.
  double max_depth_from_seed_m = 0.5;
  // A pixel joins only within this image distance of its region's seed [px]
  // (0 = no limit): with many seeds on a mover the union still covers it,
  // while a leak into a touching surface stays local. About a third of a
  // person's width at 2 m.
  double max_distance_from_seed_px = 40.0;
  // Pixels per region at most [px]; a region that reaches it stops growing
  // (a bad seed cannot flood the whole frame).
  int max_region_pixels = 60000;
  // Valid depths [m].
  double min_depth_m = 0.1;
  double max_depth_m = 6.0;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

// `depth`: CV_32FC1 metres (0 / NaN = invalid). `seeds`: pixels of dynamic
// points; seeds on invalid depth are ignored. Returns CV_8UC1, 255 = dynamic,
// same size as `depth`.
cv::Mat GrowDynamicRegions(const cv::Mat& depth, const std::vector<cv::Point2f>& seeds,
                           const RegionGrowingOptions& options);

}  // namespace dlslam::dynamic
