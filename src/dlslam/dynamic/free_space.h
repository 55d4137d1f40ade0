#pragma once
// The dense half of the geometry check: the current depth image against the
// depth images of a few recent frames. A pixel whose 3-D point lies in space
// an earlier view saw through (that view's depth along the ray is clearly
// farther) was not there then: something moved in. The point check
// (multiview.h) needs a reference keypoint behind the mover, so it misses a
// person in front of a textureless wall; on the real Bonn crowd it left half
// the people's keypoints in (a walker's head and shoulders held 60-75 % of
// the tracking inliers in frames 34-41, which pulled geometry mode 0.25 m).
// Free space is free whatever stood there before, so a view's own movers
// need no mask.
//
// The work is done on a grid of cells (4 x 4 px by default): a kept view
// stores the nearest depth of each cell, and the current cell's centre
// depth is compared with the nearest kept depth within neighbourhood_cells
// of where it projects. The nearest, and a cell without depth making its
// neighbourhood unknown, keep the test one-sided: depth edges, slanted
// floors and a pose a few pixels off read "occluded" or "agrees", never
// "seen through".
//
//   FreeSpaceCheck check(camera);
//   check.Offer(depth_0, cam_from_world_0);   // after each tracked frame
//   cv::Mat moved = check.Violations(depth_t, cam_from_world_t);

#include <opencv2/core.hpp>

#include <deque>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::dynamic {

struct FreeSpaceOptions {
  // Run the dense check at all (mode geometry and full).
  bool enabled = true;
  // Side of the grid cells [px, 1..32].
  int cell_px = 4;
  // Every this many offered frames one is kept as a view [frames, >= 1] ...
  int view_every_frames = 5;
  // ... and this many views at most, the oldest dropped [>= 1]: baselines of
  // up to view_every_frames x max_views frames (half a second at 30 Hz),
  // long enough for a slow walker to leave the space they stood in.
  int max_views = 3;
  // The kept depth compared is the nearest within this many cells of the
  // projection [cells, >= 0]: absorbs pose and depth-edge errors of up to
  // about (neighbourhood_cells + 0.5) x cell_px pixels.
  int neighbourhood_cells = 2;
  // "Seen through" means farther by more than depth_threshold_m +
  // depth_threshold_per_m2 x depth^2 [m, 1/m] (a structured-light sensor's
  // error grows with the square of the depth), as the point check.
  double depth_threshold_m = 0.04;
  double depth_threshold_per_m2 = 0.006;
  // Connected violations smaller than this are noise [cells, >= 1].
  int min_region_cells = 16;
  // A view violated on more than this share of the cells compared with it
  // is misposed (a tracking error, a map correction), not looking at movers:
  // it is ignored [0..1].
  double max_violated_share = 0.4;
  // Depths outside this range are not used [m].
  double min_depth_m = 0.1;
  double max_depth_m = 6.0;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

struct FreeSpaceStats {
  int views = 0;            // views kept when checked
  int views_ignored = 0;    // of those, misposed (max_violated_share)
  int cells_compared = 0;   // summed over the views used
  int cells_violated = 0;   // after the noise filter, in any view
};

class FreeSpaceCheck {
 public:
  explicit FreeSpaceCheck(const CameraIntrinsics& camera, const FreeSpaceOptions& options = {});

  // A frame's depth (CV_32FC1 metres, 0 / NaN = none) at its pose; kept
  // every view_every_frames-th call. Throws dlslam::Error on a depth image
  // of the wrong type or size.
  void Offer(const cv::Mat& depth, const SE3d& cam_from_world);
  // Forgets the kept views (a new map, a corrected map).
  void Reset();
  int views() const { return static_cast<int>(views_.size()); }

  // CV_8UC1 of the camera's size, 255 where the current depth (at
  // cam_from_world) stands in space a kept view saw through; empty when no
  // view is kept. Throws dlslam::Error like Offer.
  cv::Mat Violations(const cv::Mat& depth, const SE3d& cam_from_world, FreeSpaceStats* stats = nullptr) const;

 private:
  struct View {
    SE3d cam_from_world;
    cv::Mat nearest;  // CV_32FC1 per cell: nearest depth within neighbourhood_cells, 0 = unknown
  };
  void CheckDepth(const cv::Mat& depth) const;
  // Per cell: the depth at its centre pixel (0 = none).
  cv::Mat CentreDepths(const cv::Mat& depth) const;

  CameraIntrinsics camera_;
  FreeSpaceOptions options_;
  cv::Size cells_;
  std::vector<Eigen::Vector2f> rays_;  // of the cells' centres, normalised (x/z, y/z)
  std::deque<View> views_;
  int offered_ = 0;
};

}  // namespace dlslam::dynamic
