#include "dlslam/features/undistort.h"

#include <opencv2/calib3d.hpp>

namespace dlslam::features {

std::vector<cv::KeyPoint> UndistortKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                             const CameraIntrinsics& camera) {
  camera.Check();
  std::vector<cv::KeyPoint> out = keypoints;
  if (!camera.HasDistortion() || keypoints.empty()) return out;
  const cv::Matx33d k(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const cv::Vec<double, 5> distortion(camera.k1, camera.k2, camera.p1, camera.p2, camera.k3);
  std::vector<cv::Point2f> points(keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) points[i] = keypoints[i].pt;
  std::vector<cv::Point2f> undistorted;
  // More iterations than OpenCV's default 5: the Kinect's fr1/fr2 models need
  // them to converge near the image corners.
  cv::undistortPoints(points, undistorted, k, distortion, cv::noArray(), k,
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-8));
  for (size_t i = 0; i < out.size(); ++i) out[i].pt = undistorted[i];
  return out;
}

}  // namespace dlslam::features
