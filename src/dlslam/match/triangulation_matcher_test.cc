#include "dlslam/match/triangulation_matcher.h"

#include <gtest/gtest.h>

#include <set>

#include "dlslam/util/check.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

SE3d SecondView() {
  Vector6d xi;
  xi << 0.25, -0.03, 0.05, 0.01, -0.05, 0.01;
  return SE3d::Exp(xi);
}

TEST(FundamentalMatrix, TrueCorrespondencesLieOnTheirEpipolarLines) {
  const CameraIntrinsics cam = CameraPreset("freiburg3");
  const SE3d pose2 = SecondView();
  const Eigen::Matrix3d f = FundamentalMatrix(cam, SE3d(), cam, pose2);
  for (const Eigen::Vector3d& world : {Eigen::Vector3d(0.3, -0.2, 2.0), Eigen::Vector3d(-1, 0.5, 4.0)}) {
    const Eigen::Vector2d x1 = cam.Project(world);
    const Eigen::Vector2d x2 = cam.Project(pose2 * world);
    const Eigen::Vector3d line = f * x1.homogeneous();
    EXPECT_LT(std::abs(x2.homogeneous().dot(line)) / line.head<2>().norm(), 1e-9);
  }
}

TEST(SearchForTriangulation, PairsKeypointsOfTheSameLandmark) {
  testing::LandmarkScene scene = testing::LandmarkScene::Room(3000, 5);
  scene.max_depth = 3.0;  // far keypoints have no depth: the case triangulation is for
  std::vector<int> lm1, lm2;
  const auto f1 = scene.MakeFrame(SE3d(), 0, 1, 0.5, 8, &lm1);
  const auto f2 = scene.MakeFrame(SecondView(), 1, 2, 0.5, 8, &lm2);
  const std::vector<MapPointId> none1(f1->size(), kNoId), none2(f2->size(), kNoId);
  const auto pairs = SearchForTriangulation(*f1, SE3d(), none1, *f2, SecondView(), none2);
  int right = 0;
  for (const auto& [i1, i2] : pairs) right += lm1[i1] == lm2[i2];
  const std::set<int> in1(lm1.begin(), lm1.end());
  int common = 0;
  for (int l : lm2) common += in1.count(l);
  EXPECT_GT(static_cast<double>(right), 0.98 * static_cast<double>(pairs.size()));
  EXPECT_GT(right, common / 2);
  // Keypoints that hold a point are left out.
  std::vector<MapPointId> taken1 = none1;
  for (const auto& [i1, i2] : pairs) taken1[i1] = 1;
  EXPECT_TRUE(SearchForTriangulation(*f1, SE3d(), taken1, *f2, SecondView(), none2).empty());
}

TEST(TriangulationMatchOptions, Check) {
  TriangulationMatchOptions o;
  o.max_distance = 300;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
