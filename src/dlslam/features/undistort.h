#pragma once
// Undistortion of keypoint positions with the camera's lens model.

#include <opencv2/core.hpp>

#include <vector>

#include "dlslam/data/camera.h"

namespace dlslam::features {

// The keypoints with their positions undistorted (cv::undistortPoints with
// the camera's K and k1 k2 p1 p2 k3, re-projected with K); everything else
// unchanged. Without distortion the positions are returned as they are.
// Throws dlslam::Error for invalid intrinsics.
std::vector<cv::KeyPoint> UndistortKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                             const CameraIntrinsics& camera);

}  // namespace dlslam::features
