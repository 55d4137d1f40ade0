#pragma once
// Carries a dynamic mask segmented on an earlier frame s to a later frame t
// (issue 15: the tracker uses the newest mask there is instead of waiting
// for the network). The work is done on a grid of cells (4 x 4 px by
// default: the carried mask is grown by 8-24 px for what the people did
// meanwhile, so a finer outline buys nothing and costs the tracking thread
// 4 ms a frame): every cell the mask touches is unprojected in s at its
// centre's depth, moved by the camera motion t_from_s and projected into t;
// cells without depth take the median depth of the masked ones. The carried
// cells are closed into regions, grown by `grow_px` (rounded up to whole
// cells) and drawn back at full resolution.
//
//   MaskWarper warper(camera);
//   cv::Mat mask_t = warper.Warp(mask_s, depth_s, t_from_s, /*grow_px=*/6);

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::dynamic {

struct MaskWarpOptions {
  int cell_px = 4;   // side of the grid cells the mask is carried in [px, >= 1]; 1 = every pixel
  int close_px = 3;  // closing radius joining the carried cells [px, >= 0; rounded up to cells]

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

class MaskWarper {
 public:
  // Precomputes the undistorted ray of every cell's centre pixel.
  explicit MaskWarper(const CameraIntrinsics& camera, const MaskWarpOptions& options = {});

  // mask_s: CV_8UC1 (non-zero = dynamic) of frame s; depth_s: CV_32FC1 [m]
  // of frame s (0 = none; empty or without depth on the mask: the mask
  // stays where it was and is only closed and grown); t_from_s: the camera
  // motion (cam_t_from_cam_s). Returns CV_8UC1 0/255 of frame t. Throws
  // dlslam::Error for sizes or types other than the camera's.
  cv::Mat Warp(const cv::Mat& mask_s, const cv::Mat& depth_s, const SE3d& t_from_s, int grow_px) const;

 private:
  CameraIntrinsics camera_;
  MaskWarpOptions options_;
  std::vector<Eigen::Vector2f> rays_;  // of the cells' centres, row-major, normalised (x/z, y/z)
  cv::Size cells_;                     // the grid: ceil(width / cell) x ceil(height / cell)
};

}  // namespace dlslam::dynamic
