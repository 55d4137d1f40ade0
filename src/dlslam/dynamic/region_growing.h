#pragma once
// Grows the dynamic regions of the current frame from seed pixels over the
// depth image: a 4-connected flood fill that crosses from a pixel to its
// neighbour only when their depths are close, so it stops at depth
// discontinuities (the silhouette of a person against the background).
//
// Where a mover touches the scene (feet on the floor, a hand on a desk) the
// depth is continuous and a plain fill leaks. Two stops bound that:
// - static evidence competes: the pixels of points the multi-view test found
//   static are grown in the same breadth-first fill (after a head start of
//   the dynamic ones), and a pixel belongs to whichever fill reaches it
//   first (a geodesic Voronoi split of the depth-continuous surface), so a
//   dynamic region ends about halfway (plus the head start) to the nearest
//   static point on the floor or wall;
// - a size in metres: a pixel joins only within a 3-D distance of its seed's
//   point (a person is ~0.6 m wide at any range), so a region far from any
//   static point still stays local; many seeds on a mover cover it.

#include <opencv2/core.hpp>

#include <vector>

#include "dlslam/data/camera.h"

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
  // A pixel joins only when its 3-D point lies within this distance of its
  // seed's 3-D point [m] (0 = no limit). Metric, so a region has the same
  // physical size near and far; with many seeds on a mover the union covers
  // it, while a leak into a touching surface stays local.
  double max_distance_from_seed_m = 0.45;
  // Grow the static points too, and let them claim pixels before a dynamic
  // fill gets there (static evidence as a barrier).
  bool static_points_compete = true;
  // Dynamic fills get this head start [px] before the static points start
  // to grow: static points within it of a dynamic region are overrun (on a
  // slowly moving person many points still test static next to the ones
  // that test dynamic), while static evidence farther out still closes
  // the floor and walls. 0 = a fair race.
  int static_head_start_px = 20;
  // A static fill claims pixels only within this 3-D distance of its point
  // [m] (0 = no limit); bounds its cost. Smaller values (0.15) were tried so
  // that a stray static point on a mover would take only a small disc: no
  // gain on the twins, and the floor then leaks between the discs.
  double static_distance_from_seed_m = 0.45;
  // Grow on every pixel_step-th pixel in u and v (1 or 2) and upsample the
  // result: 2 is 4x faster and only coarsens the outline by a pixel, which
  // the fusion's dilation covers. The depth steps allowed between grid
  // neighbours scale with it.
  int pixel_step = 2;
  // Image pixels per region at most [px] (counted on the grid, a grid
  // pixel standing for pixel_step^2); a region that reaches it stops growing
  // (a bad seed cannot flood the whole frame).
  int max_region_pixels = 60000;
  // Valid depths [m].
  double min_depth_m = 0.1;
  double max_depth_m = 6.0;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

// `depth`: CV_32FC1 metres (0 / NaN = invalid), `camera.width` x
// `camera.height` (its pinhole part unprojects pixels for the metric size
// limit; distortion is ignored there). `dynamic_seeds`: pixels of dynamic
// points; `static_seeds`: pixels of static points (barriers; may be empty).
// Seeds outside the image or on invalid depth are ignored. Returns CV_8UC1,
// 255 = dynamic, same size as `depth`. Throws dlslam::Error on a depth image
// of the wrong type or size.
// The working memory of GrowDynamicRegions (a 320x240 grid: ~1.5 MB). A
// caller that grows every frame keeps one and passes it, so that nothing is
// allocated per call; none: the call allocates its own.
struct RegionGrowingBuffers {
  struct Cell {
    float z, x, y;  // depth and 3-D point in the camera frame [m]
    int seed;       // the fill that claimed the cell
  };
  struct Seed {
    float x, y, z;  // 3-D point in the camera frame [m]
    int pixels;     // claimed so far
  };
  std::vector<Cell> cells;
  cv::Mat owner_kind;
  std::vector<float> ray_x;
  std::vector<Seed> seeds;
  std::vector<int> queue;
};

cv::Mat GrowDynamicRegions(const cv::Mat& depth, const CameraIntrinsics& camera,
                           const std::vector<cv::Point2f>& dynamic_seeds,
                           const std::vector<cv::Point2f>& static_seeds,
                           const RegionGrowingOptions& options, RegionGrowingBuffers* buffers = nullptr);

}  // namespace dlslam::dynamic
