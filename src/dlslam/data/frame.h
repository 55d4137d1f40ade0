#pragma once
// A frame ready for tracking: undistorted keypoints with depth and the RGB-D
// virtual right coordinate, their descriptors and a grid for radius search.
// Dynamic regions are removed by making a frame without their keypoints
// (WithoutMasked): tracking and mapping only ever see static keypoints, so no
// matcher can forget to skip moving ones.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <optional>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam {

// Scale of each pyramid level, shared by the extractor and the tracker.
struct ScalePyramid {
  int levels = 8;             // number of pyramid levels
  double scale_factor = 1.2;  // size ratio between consecutive levels

  double Scale(int level) const;          // scale_factor^level
  double InverseSigma2(int level) const;  // 1 / scale^2: information of a keypoint
  void Check() const;
};

struct FrameKeypoint {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // undistorted pixel [px]
  Eigen::Vector2f raw_uv = Eigen::Vector2f::Zero();  // as detected (distorted) [px]
  double depth = 0.0;     // [m]; 0 = no valid depth
  double right_u = -1.0;  // virtual right-image u [px]; < 0 = no depth
  int octave = 0;
  float angle = 0.f;  // [deg], as cv::KeyPoint
  float response = 0.f;
};

class Frame {
 public:
  // `keypoints` as detected on the (distorted) colour image; `descriptors`
  // one row each (CV_8UC1, 32 bytes for ORB). `depth` CV_32FC1 metres
  // registered to the colour image (0 = invalid); keypoint depth is read at
  // the detected pixel. Depth outside (min_depth, max_depth) counts as none.
  static Frame Create(double timestamp, const std::vector<cv::KeyPoint>& keypoints, cv::Mat descriptors,
                      const cv::Mat& depth, const CameraIntrinsics& camera, const ScalePyramid& pyramid,
                      double min_depth = 0.1, double max_depth = 20.0);

  // A frame from keypoints already made (a saved map's keyframes): `keypoints`
  // as FrameKeypoint (undistorted, with depth), one descriptor row each.
  static Frame FromKeypoints(double timestamp, std::vector<FrameKeypoint> keypoints, cv::Mat descriptors,
                             const CameraIntrinsics& camera, const ScalePyramid& pyramid);

  double timestamp() const { return timestamp_; }
  const CameraIntrinsics& camera() const { return camera_; }
  const ScalePyramid& pyramid() const { return pyramid_; }
  std::size_t size() const { return keypoints_.size(); }
  const FrameKeypoint& keypoint(std::size_t i) const { return keypoints_[i]; }
  const std::vector<FrameKeypoint>& keypoints() const { return keypoints_; }
  const cv::Mat& descriptors() const { return descriptors_; }
  const uchar* descriptor(std::size_t i) const { return descriptors_.ptr<uchar>(static_cast<int>(i)); }

  // Per keypoint: whether its detected pixel falls on a non-zero pixel of
  // `mask` (CV_8UC1, the colour image's size; keypoints outside it: false).
  std::vector<bool> OnMask(const cv::Mat& mask) const;
  // The same frame with only the keypoints i where keep[i] (same order).
  Frame Subset(const std::vector<bool>& keep) const;
  // The same frame without the keypoints on `mask` (e.g. dynamic regions).
  Frame WithoutMasked(const cv::Mat& mask) const;

  // Indices of keypoints within `radius` px of (u, v) (undistorted), with
  // octave in [min_octave, max_octave] (negative = no bound), grid cell by
  // cell (row-major), ascending within a cell. The second form fills `out`
  // (cleared first), so a matcher's loop reuses one buffer.
  std::vector<int> FeaturesInArea(double u, double v, double radius, int min_octave = -1,
                                  int max_octave = -1) const;
  void FeaturesInArea(double u, double v, double radius, int min_octave, int max_octave,
                      std::vector<int>& out) const;

  // Point in the camera frame of keypoint i, if it has depth.
  std::optional<Eigen::Vector3d> Unproject(std::size_t i) const;

  const std::optional<SE3d>& cam_from_world() const { return cam_from_world_; }
  void set_cam_from_world(const SE3d& pose) { cam_from_world_ = pose; }

 private:
  static constexpr int kGridCols = 64;
  static constexpr int kGridRows = 48;
  void BuildGrid();

  double timestamp_ = 0.0;
  CameraIntrinsics camera_;
  ScalePyramid pyramid_;
  std::vector<FrameKeypoint> keypoints_;
  cv::Mat descriptors_;
  // Undistorted image bounds covered by the grid.
  double min_u_ = 0, max_u_ = 0, min_v_ = 0, max_v_ = 0;
  double cell_w_inv_ = 0, cell_h_inv_ = 0;
  // The grid, cell by cell (row-major): the keypoints of cell c are
  // grid_[cell_start_[c] .. cell_start_[c + 1]), so a row of cells is one
  // contiguous range, with the position and octave beside the index.
  struct GridEntry {
    Eigen::Vector2d uv;
    int octave = 0;
    int index = 0;
  };
  std::vector<int> cell_start_;  // kGridRows * kGridCols + 1
  std::vector<GridEntry> grid_;
  std::optional<SE3d> cam_from_world_;
};

}  // namespace dlslam
