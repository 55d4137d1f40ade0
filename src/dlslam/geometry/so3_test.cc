#include "dlslam/geometry/so3.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tests/support/numeric_diff.h"

namespace dlslam {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Eigen::Vector3d> SampleTangents() {
  std::vector<Eigen::Vector3d> out = {
      Eigen::Vector3d::Zero(), Eigen::Vector3d(1e-9, -2e-9, 0.5e-9),
      Eigen::Vector3d(1e-4, 0, 0), Eigen::Vector3d(0.3, -0.2, 0.1),
      Eigen::Vector3d(0, 0, kPi - 1e-6), Eigen::Vector3d(2.0, 1.0, -0.5).normalized() * 3.0};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.8, 1.8);
  for (int i = 0; i < 50; ++i) out.emplace_back(u(rng), u(rng), u(rng));
  return out;
}

TEST(SO3, ExpLogRoundTrip) {
  for (const auto& w : SampleTangents()) {
    const Eigen::Vector3d back = SO3d::Exp(w).Log();
    EXPECT_LT((back - w).norm(), 1e-9 * std::max(1.0, w.norm())) << w.transpose();
  }
}

TEST(SO3, ExpMatchesAngleAxis) {
  for (const auto& w : SampleTangents()) {
    if (w.norm() < 1e-12) continue;
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
    EXPECT_LT((SO3d::Exp(w).matrix() - expected).norm(), 1e-12);
  }
}

TEST(SO3, LogOfNegatedQuaternionIsTheSame) {
  const Eigen::Vector3d w(0.4, -1.1, 0.7);
  const Eigen::Quaterniond q = SO3d::Exp(w).quaternion();
  const SO3d negated(Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z()));
  EXPECT_LT((negated.Log() - w).norm(), 1e-12);
}

TEST(SO3, HatVeeAndAdjoint) {
  const Eigen::Vector3d a(0.1, 0.2, -0.3), b(-1, 2, 0.5);
  EXPECT_LT((SO3d::Hat(a) * b - a.cross(b)).norm(), 1e-15);
  EXPECT_EQ(SO3d::Vee(SO3d::Hat(a)), a);
  const SO3d R = SO3d::Exp(Eigen::Vector3d(0.5, -0.4, 1.2));
  const SO3d lhs = R * SO3d::Exp(a) * R.Inverse();
  EXPECT_LT((lhs.Log() - R.Adj() * a).norm(), 1e-12);
}

TEST(SO3, GroupAxioms) {
  const SO3d a = SO3d::Exp(Eigen::Vector3d(0.3, 0.1, -0.2));
  const SO3d b = SO3d::Exp(Eigen::Vector3d(-1.0, 0.4, 0.9));
  const Eigen::Vector3d p(1, -2, 3);
  EXPECT_LT(((a * b) * p - a * (b * p)).norm(), 1e-14);
  EXPECT_LT((a * a.Inverse()).Log().norm(), 1e-15);
  EXPECT_LT(((a * b).matrix() - a.matrix() * b.matrix()).norm(), 1e-14);
}

TEST(SO3, JacobiansMatchNumericDifferences) {
  for (const auto& w : SampleTangents()) {
    if (w.norm() > 3.0) continue;  // Jacobians are singular at 2 pi; log wraps at pi.
    // Right Jacobian: d/d(dw) Log(Exp(w)^-1 Exp(w + dw)) at 0.
    const auto right = [&](const Eigen::Vector3d& dw) {
      return (SO3d::Exp(w).Inverse() * SO3d::Exp(w + dw)).Log();
    };
    const auto left = [&](const Eigen::Vector3d& dw) {
      return (SO3d::Exp(w + dw) * SO3d::Exp(w).Inverse()).Log();
    };
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    EXPECT_LT((testing::NumericJacobian<3, 3>(right, zero) - SO3d::RightJacobian(w)).norm(), 1e-7);
    EXPECT_LT((testing::NumericJacobian<3, 3>(left, zero) - SO3d::LeftJacobian(w)).norm(), 1e-7);
    EXPECT_LT((SO3d::LeftJacobian(w) * SO3d::LeftJacobianInverse(w) - Eigen::Matrix3d::Identity())
                  .norm(),
              1e-9);
    EXPECT_LT((SO3d::RightJacobian(w) * SO3d::RightJacobianInverse(w) -
               Eigen::Matrix3d::Identity()).norm(),
              1e-9);
  }
}

}  // namespace
}  // namespace dlslam
