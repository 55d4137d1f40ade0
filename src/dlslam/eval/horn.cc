#include "dlslam/eval/horn.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "dlslam/util/check.h"

namespace dlslam::eval {

namespace {

Eigen::Vector3d Mean(std::span<const Eigen::Vector3d> points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

RigidAlignment AlignHorn(std::span<const Eigen::Vector3d> est, std::span<const Eigen::Vector3d> gt) {
  DLSLAM_CHECK_EQ(est.size(), gt.size(), "alignment needs corresponding points");
  DLSLAM_CHECK(!est.empty(), "alignment of no points");
  const Eigen::Vector3d est_mean = Mean(est);
  const Eigen::Vector3d gt_mean = Mean(gt);
  // W = sum_i (est_i - est_mean)(gt_i - gt_mean)^T.
  Eigen::Matrix3d w = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < est.size(); ++i) {
    w += (est[i] - est_mean) * (gt[i] - gt_mean).transpose();
  }
  RigidAlignment alignment;
  if (w.cwiseAbs().maxCoeff() > 0.0) {
    // W^T = U D V^T; R = U S V^T with S flipping the last axis when U V^T
    // would be a reflection.
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(w.transpose(),
                                               Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Matrix3d& u = svd.matrixU();
    const Eigen::Matrix3d vt = svd.matrixV().transpose();
    Eigen::Matrix3d s = Eigen::Matrix3d::Identity();
    if (u.determinant() * vt.determinant() < 0.0) s(2, 2) = -1.0;
    alignment.rotation = u * s * vt;
  }
  alignment.translation = gt_mean - alignment.rotation * est_mean;
  return alignment;
}

}  // namespace dlslam::eval
