#include "dlslam/eval/horn.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

std::vector<Eigen::Vector3d> RandomPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) points.emplace_back(u(rng), u(rng), u(rng));
  return points;
}

TEST(AlignHornTest, RecoversAKnownRigidMotion) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -1.0, 0.4).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(1.5, -2.0, 0.25);
  const std::vector<Eigen::Vector3d> est = RandomPoints(50, 1);
  std::vector<Eigen::Vector3d> gt;
  for (const auto& p : est) gt.push_back(r * p + t);
  const RigidAlignment a = AlignHorn(est, gt);
  EXPECT_LT((a.rotation - r).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((a.translation - t).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(AlignHornTest, NeverReturnsAReflection) {
  // gt is est mirrored in x: the best proper rotation, not the mirror.
  const std::vector<Eigen::Vector3d> est = RandomPoints(20, 2);
  std::vector<Eigen::Vector3d> gt;
  for (const auto& p : est) gt.emplace_back(-p.x(), p.y(), p.z());
  const RigidAlignment a = AlignHorn(est, gt);
  EXPECT_NEAR(a.rotation.determinant(), 1.0, 1e-12);
  EXPECT_LT((a.rotation * a.rotation.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(AlignHornTest, PlanarPointsStillGiveTheRotation) {
  // Motion in a plane leaves W with rank 2; the sign fix-up decides the third axis.
  std::vector<Eigen::Vector3d> est = RandomPoints(30, 3);
  for (auto& p : est) p.z() = 0.0;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(-0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<Eigen::Vector3d> gt;
  for (const auto& p : est) gt.push_back(r * p);
  EXPECT_LT((AlignHorn(est, gt).rotation - r).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(AlignHornTest, IdenticalEstimatePointsGiveIdentityNotNan) {
  const std::vector<Eigen::Vector3d> est(5, Eigen::Vector3d(1, 2, 3));
  const std::vector<Eigen::Vector3d> gt = RandomPoints(5, 4);
  const RigidAlignment a = AlignHorn(est, gt);
  EXPECT_TRUE(a.rotation.isIdentity());
  Eigen::Vector3d gt_mean = Eigen::Vector3d::Zero();
  for (const auto& p : gt) gt_mean += p / 5.0;
  EXPECT_LT((a.Apply(est[0]) - gt_mean).norm(), 1e-12);
}

TEST(AlignHornTest, BadInputThrows) {
  const std::vector<Eigen::Vector3d> three = RandomPoints(3, 5);
  const std::vector<Eigen::Vector3d> two = RandomPoints(2, 6);
  EXPECT_THROW(AlignHorn(three, two), Error);
  EXPECT_THROW(AlignHorn(std::vector<Eigen::Vector3d>{}, std::vector<Eigen::Vector3d>{}), Error);
}

}  // namespace
}  // namespace dlslam::eval
