#pragma once
// Carries a dynamic mask segmented on an earlier frame s to a later frame t
// (issue 15: the tracker uses the newest mask there is instead of waiting
// for the network). Every masked pixel with depth is unprojected in s, moved
// by the camera motion t_from_s and projected into t; pixels without depth
// take the median depth of the masked pixels that have one. The splatted
// pixels are closed into regions and grown by `grow_px` for what the people
// did in between (geometry catches the rest).
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
  int sample_step_px = 2;  // every k-th pixel of the mask is carried [px, >= 1]
  int close_px = 3;        // closing radius joining the carried samples [px, >= 0]

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

class MaskWarper {
 public:
  // Precomputes every pixel's undistorted ray (data::PixelRays).
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
  std::vector<Eigen::Vector2f> rays_;  // row-major, normalised (x/z, y/z)
};

}  // namespace dlslam::dynamic
