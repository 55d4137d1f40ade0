#include "dlslam/mapping/triangulation.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "dlslam/util/check.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

SE3d View(double x) {
  Vector6d xi;
  xi << x, -0.1 * x, 0.2 * x, 0.01, -0.2 * x, 0.01;
  return SE3d::Exp(xi);
}

struct TwoViews {
  testing::LandmarkScene scene;
  std::vector<int> lm1, lm2;
  std::shared_ptr<Frame> f1, f2;
  SE3d pose2;
  // keypoint of f2 per keypoint of f1 (-1: landmark not seen in f2)
  std::vector<int> partner;

  TwoViews(double baseline, double max_depth, double noise) : scene(testing::LandmarkScene::Room(2000, 4)) {
    scene.max_depth = max_depth;
    pose2 = View(baseline);
    f1 = scene.MakeFrame(SE3d(), 0, 1, noise, 0, &lm1);
    f2 = scene.MakeFrame(pose2, 1, 2, noise, 0, &lm2);
    std::map<int, int> in2;
    for (std::size_t j = 0; j < lm2.size(); ++j) in2[lm2[j]] = static_cast<int>(j);
    for (int l : lm1) partner.push_back(in2.count(l) ? in2[l] : -1);
  }
};

TEST(TriangulateMatch, ExactRaysWithoutDepthGiveTheLandmark) {
  const TwoViews v(0.3, 0.15, 0.0);  // no depth anywhere
  int tried = 0, accepted = 0;
  double worst = 0;
  for (std::size_t i = 0; i < v.lm1.size(); ++i) {
    if (v.partner[i] < 0) continue;
    ++tried;
    const auto p = TriangulateMatch(*v.f1, SE3d(), static_cast<int>(i), *v.f2, v.pose2, v.partner[i]);
    if (!p) continue;
    ++accepted;
    worst = std::max(worst, (*p - v.scene.points[v.lm1[i]]).norm());
  }
  ASSERT_GT(tried, 300);
  EXPECT_GT(accepted, 0.95 * tried);
  // Keypoints are stored as float pixels: ~1e-5 px, amplified by depth^2 / baseline.
  EXPECT_LT(worst, 1e-3);
}

TEST(TriangulateMatch, NoisyRaysStayCloseAndWrongPairsAreRejected) {
  const TwoViews v(0.3, 0.15, 0.5);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> any(0, static_cast<int>(v.lm2.size()) - 1);
  int accepted = 0, tried = 0, wrong_accepted = 0, wrong_tried = 0;
  std::vector<double> relative;
  for (std::size_t i = 0; i < v.lm1.size(); ++i) {
    if (v.partner[i] < 0) continue;
    ++tried;
    const Eigen::Vector3d truth = v.scene.points[v.lm1[i]];
    if (const auto p = TriangulateMatch(*v.f1, SE3d(), static_cast<int>(i), *v.f2, v.pose2, v.partner[i])) {
      ++accepted;
      relative.push_back((*p - truth).norm() / truth.z());
    }
    const int j = any(rng);
    if (v.lm2[j] == v.lm1[i]) continue;
    ++wrong_tried;
    wrong_accepted += TriangulateMatch(*v.f1, SE3d(), static_cast<int>(i), *v.f2, v.pose2, j).has_value();
  }
  EXPECT_GT(accepted, 0.9 * tried);
  std::nth_element(relative.begin(), relative.begin() + relative.size() / 2, relative.end());
  EXPECT_LT(relative[relative.size() / 2], 0.02);
  EXPECT_LT(wrong_accepted, 0.05 * wrong_tried);
}

TEST(TriangulateMatch, WithoutParallaxDepthDecidesOrNothing) {
  // 2 mm apart: rays carry no depth information.
  const TwoViews with_depth(0.002, 20.0, 0.0);
  const TwoViews without_depth(0.002, 0.15, 0.0);
  int checked = 0;
  for (std::size_t i = 0; i < with_depth.lm1.size() && checked < 50; ++i) {
    if (with_depth.partner[i] < 0) continue;
    ++checked;
    const int j = with_depth.partner[i];
    const auto p = TriangulateMatch(*with_depth.f1, SE3d(), static_cast<int>(i), *with_depth.f2, with_depth.pose2, j);
    ASSERT_TRUE(p.has_value());
    EXPECT_LT((*p - with_depth.scene.points[with_depth.lm1[i]]).norm(), 1e-3);
    EXPECT_FALSE(TriangulateMatch(*without_depth.f1, SE3d(), static_cast<int>(i), *without_depth.f2,
                                  without_depth.pose2, j)
                     .has_value());
  }
  EXPECT_EQ(checked, 50);
}

TEST(CreateNewMapPoints, TriangulatesTheFarKeypointsOfANewKeyFrame) {
  const TwoViews v(0.3, 3.0, 0.5);
  Map map;
  const KeyFrameId k1 = map.AddKeyFrame(v.f1, SE3d());
  const KeyFrameId k2 = map.AddKeyFrame(v.f2, v.pose2);
  // Depth points in k1, seen by k2 where it sees the landmark: the covisibility.
  for (std::size_t i = 0; i < v.lm1.size(); ++i) {
    if (v.f1->keypoint(i).depth <= 0) continue;
    const MapPointId p = map.AddMapPoint(v.scene.points[v.lm1[i]], k1, static_cast<int>(i));
    if (v.partner[i] >= 0) map.AddObservation(p, k2, v.partner[i]);
  }
  map.UpdateConnections(k2);
  const std::size_t before = map.NumMapPoints();
  const std::vector<MapPointId> old_points = map.GetKeyFrame(k2)->points;
  const int created = CreateNewMapPoints(&map, k2);
  EXPECT_EQ(map.NumMapPoints(), before + created);
  int far_shared = 0;
  for (std::size_t i = 0; i < v.lm1.size(); ++i) far_shared += v.partner[i] >= 0 && v.f1->keypoint(i).depth <= 0;
  EXPECT_GT(created, far_shared / 2);
  // Every new point is near its landmark.
  const auto kf2 = map.GetKeyFrame(k2);
  int checked = 0, close = 0;
  for (std::size_t j = 0; j < kf2->points.size(); ++j) {
    if (kf2->points[j] == kNoId || old_points[j] != kNoId) continue;
    const auto view = map.GetPoints({kf2->points[j]});
    ++checked;
    const Eigen::Vector3d truth = v.scene.points[v.lm2[j]];
    close += (view[0].position - truth).norm() < 0.1 * truth.z();
  }
  EXPECT_EQ(checked, created);
  EXPECT_GT(close, 0.97 * checked);
}

TEST(TriangulationOptions, Check) {
  TriangulationOptions o;
  o.max_cos_parallax = 1.0;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
