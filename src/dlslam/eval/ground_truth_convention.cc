#include "dlslam/eval/ground_truth_convention.h"

#include <Eigen/SVD>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

// The transforms of the dataset's compute_global_transformation.py.
SE3d RosAxes() {
  Eigen::Matrix4d m;
  m << -1, 0, 0, 0,  //
      0, 0, 1, 0,    //
      0, 1, 0, 0,    //
      0, 0, 0, 1;
  return SE3d(m);
}

SE3d MarkerFromCamera() {
  Eigen::Matrix3d scaled_rotation;
  scaled_rotation << 1.0157, 0.1828, -0.2389,  //
      0.0009, -0.8431, -0.6413,                //
      -0.3009, 0.6147, -0.8085;
  // The nearest rotation: U * V^T of the SVD (the singular values are all
  // 1.0593: a uniform scale).
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(scaled_rotation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d rotation = svd.matrixU() * svd.matrixV().transpose();
  return SE3d(SO3d(rotation), Eigen::Vector3d(0.0113, -0.0098, 0.0111));
}

}  // namespace

const char* ToString(GroundTruthConvention convention) {
  switch (convention) {
    case GroundTruthConvention::kAsPublished: return "published";
    case GroundTruthConvention::kBonnCamera: return "bonn-camera";
  }
  return "?";
}

GroundTruthConvention ParseGroundTruthConvention(const std::string& name) {
  for (const GroundTruthConvention c : {GroundTruthConvention::kAsPublished, GroundTruthConvention::kBonnCamera}) {
    if (name == ToString(c)) return c;
  }
  throw Error(fmt::format("unknown ground-truth convention '{}': published | bonn-camera", name));
}

SE3d BonnCameraFromMarker(const SE3d& world_from_marker) {
  static const SE3d ros = RosAxes();
  static const SE3d marker_from_camera = MarkerFromCamera();
  return ros * world_from_marker * ros * marker_from_camera;
}

Trajectory ToCameraPoses(const Trajectory& ground_truth, GroundTruthConvention convention) {
  if (convention == GroundTruthConvention::kAsPublished) return ground_truth;
  Trajectory out;
  out.reserve(ground_truth.size());
  for (const StampedPose& p : ground_truth) out.emplace_back(p.timestamp, BonnCameraFromMarker(p.world_from_cam()));
  return out;
}

}  // namespace dlslam::eval
