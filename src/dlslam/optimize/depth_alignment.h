#pragma once
// Dense, robust alignment of two depth images (projective point-to-plane
// ICP): the camera motion that the static scene explains.
//
// Why: ORB keypoints gather on texture, and in a crowd the texture is the
// people (on the real Bonn crowd frames 40 % of the keypoints lie on a person
// covering 25 % of the image). A pose from keypoints then follows the people,
// and a multi-view check run with that pose flags the background as moving.
// Depth pixels cover the untextured walls, floor and furniture as well: most
// of them are static even when most keypoints are not, so a robust fit on
// them (movers become outliers) gives the static motion.
//
//   DepthAligner aligner(camera, options);                 // ray table once per camera
//   DepthAlignment a = aligner.Align(reference_depth, current_depth, guess_current_from_reference);
//   if (a.converged) cam_from_world = a.current_from_reference * reference_cam_from_world;

#include <opencv2/core.hpp>

#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam {

struct DepthAlignmentOptions {
  // Pixels sampled from the current image: every `sample_step`-th in each
  // direction [px, >= 1] (4: ~19k samples at 640x480).
  int sample_step = 4;
  // Gauss-Newton iterations (each re-associates projectively) [count, >= 1].
  int iterations = 12;
  // Expected point-to-plane noise sigma(z) = noise_m + noise_per_m2 * z^2 [m,
  // 1/m]: a structured-light sensor's depth error grows with z^2 (Kinect /
  // Xtion: ~1.4e-3 z^2, Khoshelham & Elberink 2012) plus the registration
  // and quantisation floor.
  double noise_m = 0.003;
  double noise_per_m2 = 1.5e-3;
  // Residuals beyond this many sigmas get no weight (Tukey's biweight; the
  // first iterations use a wider kernel), and correspondences farther apart
  // than `max_distance_m` are not paired.
  double tukey_sigmas = 3.0;
  double max_distance_m = 0.15;
  // Depths used [m].
  double min_depth_m = 0.2;
  double max_depth_m = 6.0;
  // Stop when the update is below this [m, or rad].
  double min_step = 1e-5;
  // An alignment counts only with this many inlier samples [count].
  int min_inliers = 300;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

struct DepthAlignment {
  SE3d current_from_reference;
  bool converged = false;   // enough inliers and a well-conditioned fit
  int samples = 0;          // current pixels with valid depth that were used
  int inliers = 0;          // of those, agreeing with the reference within 3 sigma
  double inlier_fraction = 0.0;  // inliers / samples
  int iterations = 0;
};

// A reference depth image made ready for alignment: half resolution,
// denoised (2x2 blocks, then a 3x3 mean of blocks on the same surface), so
// that the normals of far, noisy surfaces stay usable. Its buffer is reused
// by the next Prepare into it.
struct PreparedDepth {
  cv::Mat half;  // CV_32FC1 metres, (height / 2) x (width / 2), 0 = none
  cv::Mat blocks;  // scratch
};

class DepthAligner {
 public:
  // Precomputes the undistorted ray of every pixel (the depth image is on the
  // colour camera's distorted grid). Throws on invalid options or camera.
  DepthAligner(const CameraIntrinsics& camera, const DepthAlignmentOptions& options = {});

  // Depths: CV_32FC1 metres, camera size, 0 / NaN = none. `guess`: the
  // starting current_from_reference. Throws dlslam::Error on a wrong image.
  DepthAlignment Align(const cv::Mat& reference_depth, const cv::Mat& current_depth, const SE3d& guess) const;
  // The same with a reference prepared once for several alignments.
  DepthAlignment Align(const PreparedDepth& reference, const cv::Mat& current_depth, const SE3d& guess) const;
  PreparedDepth Prepare(const cv::Mat& depth) const;
  void Prepare(const cv::Mat& depth, PreparedDepth* out) const;

  // How well `current_from_reference` explains the current depth, without
  // refining it: the same counts as Align (converged unset).
  DepthAlignment Score(const cv::Mat& reference_depth, const cv::Mat& current_depth,
                       const SE3d& current_from_reference) const;
  DepthAlignment Score(const PreparedDepth& reference, const cv::Mat& current_depth,
                       const SE3d& current_from_reference) const;

  const DepthAlignmentOptions& options() const { return options_; }

 private:
  void BuildRays();
  struct Sample {
    Eigen::Vector3f point;  // in the current camera [m]
  };
  // The point of pixel (u, v) of `depth` in its camera, false if no depth.
  bool PointAt(const cv::Mat& depth, int u, int v, Eigen::Vector3f* point) const;
  // The reference's point and normal at the pixel where `p_ref` projects.
  bool Correspondence(const cv::Mat& reference_half, const Eigen::Vector3f& p_ref, Eigen::Vector3f* q,
                      Eigen::Vector3f* normal) const;
  // The point of pixel (u, v) of a half-resolution depth image.
  bool HalfPointAt(const cv::Mat& half, int u, int v, Eigen::Vector3f* point) const;
  std::vector<Sample> Samples(const cv::Mat& current_depth) const;
  void CheckDepth(const cv::Mat& depth, const char* what) const;
  // One pass over the samples: normal equations (when h/g are given) and counts.
  void Accumulate(const cv::Mat& reference_depth, const std::vector<Sample>& samples,
                  const SE3d& reference_from_current, Eigen::Matrix<double, 6, 6>* h,
                  Eigen::Matrix<double, 6, 1>* g, int* inliers, double kernel_scale) const;

  CameraIntrinsics camera_;
  DepthAlignmentOptions options_;
  std::vector<Eigen::Vector2f> rays_;       // undistorted (x/z, y/z) per pixel, row-major
  std::vector<Eigen::Vector2f> half_rays_;  // the same per 2x2 block (its centre)
};

}  // namespace dlslam
