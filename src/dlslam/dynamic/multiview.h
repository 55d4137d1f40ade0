#pragma once
// Multi-view consistency check (after DynaSLAM, paper Sec. III-C): keypoints
// with depth of earlier keyframes ("reference views") are projected into the
// current frame and compared with the current depth image.
//
//   current depth << projected depth : something now stands in front of the
//                                      point -> the current pixel is dynamic;
//   current depth >> projected depth : the earlier point itself has left
//                                      (it was on a moving object) -> vanished;
//   otherwise                        : static.
//
// Points seen under viewing rays more than ~30 deg apart are not used to
// decide (occlusion by static structure and surface slant make them
// unreliable).

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::dynamic {

struct MultiViewOptions {
  // Reference views used per frame (the first ones of the list the caller
  // passes, so the caller orders them by relevance) [count, >= 1].
  int max_reference_views = 5;
  // Points whose viewing rays from the reference and the current camera
  // centre differ by more than this are unreliable [deg] (DynaSLAM: 30).
  double max_view_angle_deg = 30.0;
  // Depth-difference threshold th(z) = depth_threshold_m +
  // depth_threshold_per_m2 * z^2, z = projected depth [m]. The constant part
  // [m] covers pose error and the distance to the nearest valid depth pixel.
  double depth_threshold_m = 0.04;
  // Growth with depth [1/m]: the Kinect's depth noise has a standard
  // deviation of about 1.4e-3 * z^2 m (Khoshelham & Elberink 2012) for each
  // of the two measurements compared; 3 sigma of their difference is
  // 3 * sqrt(2) * 1.4e-3 ~ 6e-3.
  double depth_threshold_per_m2 = 6e-3;
  // The current depth is the valid pixel nearest to the projection within
  // this Chebyshev radius [px]; none -> unknown.
  int depth_patch_radius_px = 2;
  // A point whose depth disagrees is still static when a valid depth within
  // this Chebyshev radius [px] agrees with it (0 = off): near a depth edge
  // a static point projected a pixel or two off reads the other side of the
  // edge (pose error, colour-depth registration, parallax at silhouettes),
  // and on the real Bonn frames such points seeded regions over whole
  // static chairs, desks and shelves.
  int agreement_radius_px = 3;
  // A point hidden behind a nearer surface proves motion only if that
  // surface, were it static, would also have stood on the reference view's
  // ray to the point (which that view saw). Checked where the ray crosses the
  // surface's depth: free space there now means the reference view saw past
  // the surface, and the occlusion is the camera's parallax (kOccluded).
  // Why: on the real Bonn crowd, wall points seen beside a chair's back from
  // one keyframe fell behind it from the current view and grew regions over
  // whole static chairs and floor. False = off.
  bool parallax_occlusion_check = true;
  // ... and only where the ray passes the surface by at least this many
  // pixels [px, 0..20]: near a silhouette pose error and the nearest-depth
  // search blur the test, and thin movers (an arm, a head) must keep it.
  int parallax_clearance_px = 4;
  // Depths outside [min_depth_m, max_depth_m] (projected or measured) are
  // treated as invalid [m]; beyond ~5 m the Kinect's depth is too noisy.
  double min_depth_m = 0.1;
  double max_depth_m = 6.0;

  // th(z) [m] for a projected depth z [m].
  double DepthThreshold(double z) const {
    return depth_threshold_m + depth_threshold_per_m2 * z * z;
  }
  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

// One keypoint with depth of an earlier keyframe.
struct ReferencePoint {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();  // [m]
  // A map point id or any tag of the caller; reported for vanished points.
  std::uint64_t id = std::numeric_limits<std::uint64_t>::max();
};

// An earlier keyframe: its pose and its keypoints with depth.
struct ReferenceView {
  SE3d cam_from_world;
  std::vector<ReferencePoint> points;
};

enum class PointLabel : std::uint8_t {
  kUntested,    // never tested (skipped by the search)
  kUnknown,     // no valid current depth near the projection
  kUnreliable,  // viewing rays too far apart
  kStatic,      // depths agree
  kDynamic,     // something now stands in front of the point
  kVanished,    // the point has left (current depth clearly larger)
  kOccluded,    // behind a nearer surface the reference view saw past (parallax)
};
const char* ToString(PointLabel label);

// A reference point seen in the current frame.
struct ProjectedPoint {
  // Current image position [px], on the distorted grid of the depth image.
  Eigen::Vector2f pixel = Eigen::Vector2f::Zero();
  float projected_depth = 0;  // z in the current camera [m]
  float view_angle_deg = 0;   // angle between the two viewing rays [deg]
  int view = 0;               // index into the reference views
  int point = 0;              // index into that view's points
};

// Projects the points of the first `max_views` `references` into the
// current camera (cam_from_world, intrinsics incl. distortion); keeps those
// in front of the camera (z > 0) whose pixel lies inside the image. Clears
// `out` first (so a caller can reuse its buffer).
void ProjectReferencePoints(const std::vector<ReferenceView>& references,
                            const SE3d& cam_from_world, const CameraIntrinsics& intrinsics,
                            std::vector<ProjectedPoint>& out,
                            std::size_t max_views = std::numeric_limits<std::size_t>::max());
std::vector<ProjectedPoint> ProjectReferencePoints(const std::vector<ReferenceView>& references,
                                                   const SE3d& cam_from_world,
                                                   const CameraIntrinsics& intrinsics);

// Labels one projected point against the current depth image (CV_32FC1,
// metres, 0 or NaN = no measurement). Never returns kUntested. `depth_pixel`
// (optional) receives the pixel whose depth decided (for kStatic, kDynamic,
// kVanished): a dynamic point's occluder, the seed of region growing.
PointLabel ClassifyPoint(const ProjectedPoint& point, const cv::Mat& depth,
                         const MultiViewOptions& options, cv::Point* depth_pixel = nullptr);

// For a kDynamic point (`point_world`, seen from `reference_cam_from_world`;
// now behind a surface at `measured_depth` [m]): does the surface, were it
// static, also stand on the reference camera's ray to the point? Samples
// that ray where its current depth is measured_depth and measured_depth +-
// the depth threshold, and reads the current depth (CV_32FC1 metres) there.
// False (parallax explains the occlusion) only when every sample that can be
// read shows free space beyond it, within options.parallax_clearance_px, and
// at least one can; true when any shows a surface on the ray or something
// nearer hiding it, or none can be read.
bool OcclusionProvesMotion(const Eigen::Vector3d& point_world, const SE3d& reference_cam_from_world,
                           const SE3d& cam_from_world, double measured_depth, const cv::Mat& depth,
                           const CameraIntrinsics& intrinsics, const MultiViewOptions& options);

// The valid depth [m] nearest to `pixel` (rounded) within the Chebyshev
// radius: rings of growing radius, within a ring the smallest Euclidean
// distance (then row-major order); 0 when there is none. `where` (optional)
// receives its pixel.
float NearestValidDepth(const cv::Mat& depth, const Eigen::Vector2f& pixel, int radius_px,
                        float min_depth_m, float max_depth_m, cv::Point* where = nullptr);

}  // namespace dlslam::dynamic
