#include "dlslam/data/frame.h"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dlslam/util/check.h"

namespace dlslam {

double ScalePyramid::Scale(int level) const { return std::pow(scale_factor, level); }
double ScalePyramid::InverseSigma2(int level) const {
  const double s = Scale(level);
  return 1.0 / (s * s);
}
void ScalePyramid::Check() const {
  DLSLAM_CHECK_GT(levels, 0);
  DLSLAM_CHECK_GT(scale_factor, 1.0);
}

namespace {

// Undistorts keypoint pixels with the camera's distortion model.
std::vector<Eigen::Vector2d> Undistort(const std::vector<cv::KeyPoint>& keypoints,
                                       const CameraIntrinsics& camera) {
  std::vector<Eigen::Vector2d> out(keypoints.size());
  if (!camera.HasDistortion() || keypoints.empty()) {
    for (std::size_t i = 0; i < keypoints.size(); ++i) out[i] = {keypoints[i].pt.x, keypoints[i].pt.y};
    return out;
  }
  std::vector<cv::Point2f> in(keypoints.size()), undistorted;
  for (std::size_t i = 0; i < keypoints.size(); ++i) in[i] = keypoints[i].pt;
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const cv::Vec<double, 5> dist(camera.k1, camera.k2, camera.p1, camera.p2, camera.k3);
  cv::undistortPoints(in, undistorted, K, dist, cv::noArray(), K);
  for (std::size_t i = 0; i < keypoints.size(); ++i) out[i] = {undistorted[i].x, undistorted[i].y};
  return out;
}

}  // namespace

Frame Frame::Create(double timestamp, const std::vector<cv::KeyPoint>& keypoints, cv::Mat descriptors,
                    const cv::Mat& depth, const CameraIntrinsics& camera, const ScalePyramid& pyramid,
                    double min_depth, double max_depth) {
  camera.Check();
  pyramid.Check();
  DLSLAM_CHECK_EQ(descriptors.rows, static_cast<int>(keypoints.size()), "one descriptor per keypoint");
  DLSLAM_CHECK(keypoints.empty() || descriptors.type() == CV_8UC1, "descriptors must be CV_8UC1");
  DLSLAM_CHECK(depth.empty() || depth.type() == CV_32FC1, "depth must be CV_32FC1 metres");
  Frame f;
  f.timestamp_ = timestamp;
  f.camera_ = camera;
  f.pyramid_ = pyramid;
  f.descriptors_ = std::move(descriptors);
  const std::vector<Eigen::Vector2d> undistorted = Undistort(keypoints, camera);
  f.keypoints_.resize(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& k = keypoints[i];
    FrameKeypoint& fk = f.keypoints_[i];
    fk.uv = undistorted[i];
    fk.raw_uv = {k.pt.x, k.pt.y};
    fk.octave = std::clamp(k.octave, 0, pyramid.levels - 1);
    fk.angle = k.angle;
    fk.response = k.response;
    const int x = static_cast<int>(std::lround(k.pt.x));
    const int y = static_cast<int>(std::lround(k.pt.y));
    if (!depth.empty() && x >= 0 && y >= 0 && x < depth.cols && y < depth.rows) {
      const double z = depth.at<float>(y, x);
      if (z > min_depth && z < max_depth) {
        fk.depth = z;
        fk.right_u = fk.uv.x() - camera.bf / z;
      }
    }
  }
  f.BuildGrid();
  return f;
}

Frame Frame::FromKeypoints(double timestamp, std::vector<FrameKeypoint> keypoints, cv::Mat descriptors,
                           const CameraIntrinsics& camera, const ScalePyramid& pyramid) {
  camera.Check();
  pyramid.Check();
  DLSLAM_CHECK_EQ(descriptors.rows, static_cast<int>(keypoints.size()), "one descriptor per keypoint");
  DLSLAM_CHECK(keypoints.empty() || descriptors.type() == CV_8UC1, "descriptors must be CV_8UC1");
  Frame f;
  f.timestamp_ = timestamp;
  f.camera_ = camera;
  f.pyramid_ = pyramid;
  f.keypoints_ = std::move(keypoints);
  f.descriptors_ = std::move(descriptors);
  f.BuildGrid();
  return f;
}

void Frame::BuildGrid() {
  // Bounds of the undistorted image: the corners move under distortion.
  min_u_ = 0;
  min_v_ = 0;
  max_u_ = camera_.width;
  max_v_ = camera_.height;
  for (const FrameKeypoint& k : keypoints_) {
    min_u_ = std::min(min_u_, k.uv.x());
    max_u_ = std::max(max_u_, k.uv.x() + 1e-3);
    min_v_ = std::min(min_v_, k.uv.y());
    max_v_ = std::max(max_v_, k.uv.y() + 1e-3);
  }
  cell_w_inv_ = kGridCols / (max_u_ - min_u_);
  cell_h_inv_ = kGridRows / (max_v_ - min_v_);
  // A counting sort by cell keeps the keypoints' order within a cell.
  std::vector<int> cell_of(keypoints_.size());
  cell_start_.assign(kGridCols * kGridRows + 1, 0);
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    const int cx = std::clamp(static_cast<int>((keypoints_[i].uv.x() - min_u_) * cell_w_inv_), 0, kGridCols - 1);
    const int cy = std::clamp(static_cast<int>((keypoints_[i].uv.y() - min_v_) * cell_h_inv_), 0, kGridRows - 1);
    cell_of[i] = cy * kGridCols + cx;
    ++cell_start_[static_cast<std::size_t>(cell_of[i]) + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  grid_.resize(keypoints_.size());
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    grid_[static_cast<std::size_t>(next[static_cast<std::size_t>(cell_of[i])]++)] = {
        keypoints_[i].uv, keypoints_[i].octave, static_cast<int>(i)};
  }
}

std::vector<bool> Frame::OnMask(const cv::Mat& mask) const {
  DLSLAM_CHECK_EQ(mask.type(), CV_8UC1, "dynamic mask must be 8-bit single channel");
  std::vector<bool> on(keypoints_.size(), false);
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    const int x = static_cast<int>(std::lround(keypoints_[i].raw_uv.x()));
    const int y = static_cast<int>(std::lround(keypoints_[i].raw_uv.y()));
    if (x < 0 || y < 0 || x >= mask.cols || y >= mask.rows) continue;
    on[i] = mask.at<uchar>(y, x) != 0;
  }
  return on;
}

Frame Frame::Subset(const std::vector<bool>& keep) const {
  DLSLAM_CHECK_EQ(keep.size(), keypoints_.size(), "one flag per keypoint");
  Frame f;
  f.timestamp_ = timestamp_;
  f.camera_ = camera_;
  f.pyramid_ = pyramid_;
  f.cam_from_world_ = cam_from_world_;
  const int kept = static_cast<int>(std::count(keep.begin(), keep.end(), true));
  f.keypoints_.reserve(static_cast<std::size_t>(kept));
  f.descriptors_.create(kept, descriptors_.cols, descriptors_.empty() ? CV_8UC1 : descriptors_.type());
  for (std::size_t i = 0; i < keypoints_.size(); ++i) {
    if (!keep[i]) continue;
    descriptors_.row(static_cast<int>(i)).copyTo(f.descriptors_.row(static_cast<int>(f.keypoints_.size())));
    f.keypoints_.push_back(keypoints_[i]);
  }
  f.BuildGrid();
  return f;
}

Frame Frame::WithoutMasked(const cv::Mat& mask) const {
  std::vector<bool> keep = OnMask(mask);
  keep.flip();
  return Subset(keep);
}

std::vector<int> Frame::FeaturesInArea(double u, double v, double radius, int min_octave,
                                       int max_octave) const {
  std::vector<int> out;
  FeaturesInArea(u, v, radius, min_octave, max_octave, out);
  return out;
}

void Frame::FeaturesInArea(double u, double v, double radius, int min_octave, int max_octave,
                           std::vector<int>& out) const {
  out.clear();
  if (grid_.empty()) return;
  const int x0 = std::max(0, static_cast<int>(std::floor((u - radius - min_u_) * cell_w_inv_)));
  const int x1 = std::min(kGridCols - 1, static_cast<int>(std::floor((u + radius - min_u_) * cell_w_inv_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((v - radius - min_v_) * cell_h_inv_)));
  const int y1 = std::min(kGridRows - 1, static_cast<int>(std::floor((v + radius - min_v_) * cell_h_inv_)));
  if (x0 > x1) return;
  const double r2 = radius * radius;
  const Eigen::Vector2d centre(u, v);
  const int lo = min_octave >= 0 ? min_octave : std::numeric_limits<int>::min();
  const int hi = max_octave >= 0 ? max_octave : std::numeric_limits<int>::max();
  for (int cy = y0; cy <= y1; ++cy) {
    const int end = cell_start_[static_cast<std::size_t>(cy * kGridCols + x1 + 1)];
    for (int e = cell_start_[static_cast<std::size_t>(cy * kGridCols + x0)]; e < end; ++e) {
      const GridEntry& k = grid_[static_cast<std::size_t>(e)];
      if (k.octave < lo || k.octave > hi) continue;
      if ((k.uv - centre).squaredNorm() <= r2) out.push_back(k.index);
    }
  }
}

std::optional<Eigen::Vector3d> Frame::Unproject(std::size_t i) const {
  const FrameKeypoint& k = keypoints_[i];
  if (k.depth <= 0) return std::nullopt;
  return camera_.Unproject(k.uv, k.depth);
}

}  // namespace dlslam
