#include "dlslam/geometry/se3.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "tests/support/numeric_diff.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

std::vector<Vector6d> SampleTangents() {
  std::vector<Vector6d> out;
  Vector6d v;
  out.push_back(Vector6d::Zero());
  v << 1, -2, 3, 1e-10, 0, -1e-10;
  out.push_back(v);
  v << 0.1, 0.2, 0.3, 0.4, -0.5, 0.6;
  out.push_back(v);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int i = 0; i < 50; ++i) {
    for (int k = 0; k < 6; ++k) v[k] = u(rng);
    out.push_back(v);
  }
  return out;
}

TEST(SE3, ExpLogRoundTrip) {
  for (const auto& xi : SampleTangents()) {
    EXPECT_LT((SE3d::Exp(xi).Log() - xi).norm(), 1e-10) << xi.transpose();
  }
}

TEST(SE3, ExpMatchesMatrixExponential) {
  // exp of the 4x4 twist, summed as a power series (converges fast for |xi| < 3).
  for (const auto& xi : SampleTangents()) {
    const Eigen::Matrix4d A = SE3d::Hat(xi);
    Eigen::Matrix4d term = Eigen::Matrix4d::Identity(), sum = Eigen::Matrix4d::Identity();
    for (int k = 1; k < 40; ++k) {
      term = term * A / k;
      sum += term;
    }
    EXPECT_LT((SE3d::Exp(xi).matrix() - sum).norm(), 1e-11);
  }
}

TEST(SE3, ActionInverseAndComposition) {
  const auto samples = SampleTangents();
  const Eigen::Vector3d p(0.3, -1.2, 2.5);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const SE3d a = SE3d::Exp(samples[i - 1]);
    const SE3d b = SE3d::Exp(samples[i]);
    EXPECT_LT(((a * b) * p - a * (b * p)).norm(), 1e-13);
    EXPECT_LT((a.Inverse() * (a * p) - p).norm(), 1e-13);
    EXPECT_LT(((a * b).matrix() - a.matrix() * b.matrix()).norm(), 1e-13);
    const Eigen::Vector4d ph(p.x(), p.y(), p.z(), 1.0);
    EXPECT_LT(((a.matrix() * ph).head<3>() - a * p).norm(), 1e-13);
    EXPECT_LT((SE3d(a.matrix()).matrix() - a.matrix()).norm(), 1e-14);
  }
}

TEST(SE3, Adjoint) {
  for (const auto& xi : SampleTangents()) {
    const SE3d T = SE3d::Exp(xi.reverse() * 0.5);
    const SE3d lhs = T * SE3d::Exp(xi * 0.1) * T.Inverse();
    EXPECT_LT((lhs.Log() - T.Adj() * (xi * 0.1)).norm(), 1e-10);
  }
}

TEST(SE3, ActionJacobianMatchesNumeric) {
  // d(Exp(dxi) * T * p)/d(dxi) at 0 = [I, -hat(T p)].
  for (const auto& xi : SampleTangents()) {
    const SE3d T = SE3d::Exp(xi);
    const Eigen::Vector3d p(0.7, -0.1, 1.9);
    const auto f = [&](const Vector6d& d) { return Eigen::Vector3d(SE3d::Exp(d) * T * p); };
    Eigen::Matrix<double, 3, 6> J;
    J << Eigen::Matrix3d::Identity(), -SO3d::Hat(T * p);
    EXPECT_LT((testing::NumericJacobian<3, 6>(f, Vector6d::Zero()) - J).norm(), 1e-7);
  }
}

TEST(SE3, CastKeepsValues) {
  const SE3d a = SE3d::Exp(SampleTangents()[2]);
  const SE3f f = a.cast<float>();
  EXPECT_LT((f.matrix().cast<double>() - a.matrix()).norm(), 1e-6);
}

}  // namespace
}  // namespace dlslam
