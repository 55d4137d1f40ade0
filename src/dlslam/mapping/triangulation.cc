#include "dlslam/mapping/triangulation.h"

#include <Eigen/SVD>

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam {

void TriangulationOptions::Check() const {
  DLSLAM_CHECK_GE(neighbours, 0);
  DLSLAM_CHECK(max_cos_parallax > 0 && max_cos_parallax < 1, "max_cos_parallax {} outside (0, 1)", max_cos_parallax);
  DLSLAM_CHECK_GT(chi2_mono, 0.0);
  DLSLAM_CHECK_GT(chi2_stereo, 0.0);
  DLSLAM_CHECK_GE(scale_consistency, 1.0);
  match.Check();
}

namespace {

// Whitened reprojection error of a world point in a keyframe's keypoint;
// infinite behind the camera.
double ReprojectionChi2(const Frame& frame, const SE3d& cam_from_world, int i, const Eigen::Vector3d& world) {
  const Eigen::Vector3d pc = cam_from_world * world;
  if (pc.z() <= 0) return INFINITY;
  const FrameKeypoint& k = frame.keypoint(i);
  const Eigen::Vector2d uv = frame.camera().Project(pc);
  double e2 = (uv - k.uv).squaredNorm();
  if (k.right_u >= 0) {
    const double right_u = uv.x() - frame.camera().bf / pc.z();
    e2 += (right_u - k.right_u) * (right_u - k.right_u);
  }
  return e2 * frame.pyramid().InverseSigma2(k.octave);
}

// Cosine of the angle that the virtual stereo pair subtends at a keypoint's
// depth (1 without depth: no information).
double StereoParallaxCos(const Frame& frame, int i) {
  const FrameKeypoint& k = frame.keypoint(i);
  if (k.depth <= 0) return 1.0;
  const double baseline = frame.camera().bf / frame.camera().fx;
  return std::cos(2 * std::atan2(baseline / 2, k.depth));
}

std::optional<Eigen::Vector3d> LinearTriangulation(const Eigen::Vector3d& ray1, const SE3d& cam1_from_world,
                                                   const Eigen::Vector3d& ray2, const SE3d& cam2_from_world) {
  Eigen::Matrix4d a;
  const Eigen::Matrix<double, 3, 4> p1 = cam1_from_world.matrix3x4();
  const Eigen::Matrix<double, 3, 4> p2 = cam2_from_world.matrix3x4();
  a.row(0) = ray1.x() * p1.row(2) - p1.row(0);
  a.row(1) = ray1.y() * p1.row(2) - p1.row(1);
  a.row(2) = ray2.x() * p2.row(2) - p2.row(0);
  a.row(3) = ray2.y() * p2.row(2) - p2.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(a, Eigen::ComputeFullV);
  const Eigen::Vector4d x = svd.matrixV().col(3);
  if (std::abs(x.w()) < 1e-12) return std::nullopt;
  return Eigen::Vector3d(x.head<3>() / x.w());
}

}  // namespace

std::optional<Eigen::Vector3d> TriangulateMatch(const Frame& frame1, const SE3d& cam1_from_world, int i1,
                                                const Frame& frame2, const SE3d& cam2_from_world, int i2,
                                                const TriangulationOptions& options) {
  const FrameKeypoint& k1 = frame1.keypoint(i1);
  const FrameKeypoint& k2 = frame2.keypoint(i2);
  // Normalised rays (z = 1) in each camera and their angle in the world.
  const CameraIntrinsics& c1 = frame1.camera();
  const CameraIntrinsics& c2 = frame2.camera();
  const Eigen::Vector3d ray1((k1.uv.x() - c1.cx) / c1.fx, (k1.uv.y() - c1.cy) / c1.fy, 1.0);
  const Eigen::Vector3d ray2((k2.uv.x() - c2.cx) / c2.fx, (k2.uv.y() - c2.cy) / c2.fy, 1.0);
  const Eigen::Vector3d world_ray1 = cam1_from_world.so3().Inverse() * ray1;
  const Eigen::Vector3d world_ray2 = cam2_from_world.so3().Inverse() * ray2;
  const double cos_rays = world_ray1.dot(world_ray2) / (world_ray1.norm() * world_ray2.norm());
  const double cos_stereo1 = StereoParallaxCos(frame1, i1);
  const double cos_stereo2 = StereoParallaxCos(frame2, i2);
  const double cos_stereo = std::min(cos_stereo1, cos_stereo2);
  const bool has_depth = k1.depth > 0 || k2.depth > 0;

  std::optional<Eigen::Vector3d> world;
  if (cos_rays < cos_stereo && cos_rays > 0 && (has_depth || cos_rays < options.max_cos_parallax)) {
    world = LinearTriangulation(ray1, cam1_from_world, ray2, cam2_from_world);
  } else if (k1.depth > 0 && cos_stereo1 <= cos_stereo2) {
    world = cam1_from_world.Inverse() * *frame1.Unproject(i1);
  } else if (k2.depth > 0 && cos_stereo2 < cos_stereo1) {
    world = cam2_from_world.Inverse() * *frame2.Unproject(i2);
  }
  if (!world || !world->allFinite()) return std::nullopt;

  const double chi2_1 = ReprojectionChi2(frame1, cam1_from_world, i1, *world);
  const double chi2_2 = ReprojectionChi2(frame2, cam2_from_world, i2, *world);
  if (chi2_1 > (k1.right_u >= 0 ? options.chi2_stereo : options.chi2_mono)) return std::nullopt;
  if (chi2_2 > (k2.right_u >= 0 ? options.chi2_stereo : options.chi2_mono)) return std::nullopt;

  // Seen from twice as far, a patch must appear one scale factor^k smaller.
  const double dist1 = (*world - cam1_from_world.Inverse().translation()).norm();
  const double dist2 = (*world - cam2_from_world.Inverse().translation()).norm();
  if (dist1 <= 0 || dist2 <= 0) return std::nullopt;
  const double distance_ratio = dist2 / dist1;
  const double octave_ratio = frame1.pyramid().Scale(k1.octave) / frame2.pyramid().Scale(k2.octave);
  const double factor = options.scale_consistency * frame1.pyramid().scale_factor;
  if (distance_ratio * factor < octave_ratio || distance_ratio > octave_ratio * factor) return std::nullopt;
  return world;
}

int CreateNewMapPoints(Map* map, KeyFrameId keyframe, const TriangulationOptions& options) {
  options.Check();
  std::optional<KeyFrameSnapshot> current = map->GetKeyFrame(keyframe);
  if (!current) return 0;
  const Frame& frame1 = *current->frame;
  const double min_baseline =
      options.min_baseline > 0 ? options.min_baseline : frame1.camera().bf / frame1.camera().fx;
  const Eigen::Vector3d centre1 = current->cam_from_world.Inverse().translation();
  int created = 0;
  for (KeyFrameId other : map->BestCovisible(keyframe, options.neighbours, keyframe)) {
    const std::optional<KeyFrameSnapshot> neighbour = map->GetKeyFrame(other);
    if (!neighbour) continue;
    if ((neighbour->cam_from_world.Inverse().translation() - centre1).norm() < min_baseline) continue;
    const auto pairs = SearchForTriangulation(frame1, current->cam_from_world, current->points, *neighbour->frame,
                                              neighbour->cam_from_world, neighbour->points, options.match);
    for (const auto& [i1, i2] : pairs) {
      const auto world = TriangulateMatch(frame1, current->cam_from_world, i1, *neighbour->frame,
                                          neighbour->cam_from_world, i2, options);
      if (!world) continue;
      const MapPointId id = map->AddTriangulatedPoint(*world, keyframe, i1, other, i2);
      if (id == kNoId) continue;
      current->points[i1] = id;  // later neighbours do not pair this keypoint again
      ++created;
    }
  }
  return created;
}

}  // namespace dlslam
