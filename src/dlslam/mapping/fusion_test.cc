#include "dlslam/mapping/fusion.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "dlslam/util/check.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

// Two keyframes that each made their own point for every keypoint with depth
// (the duplicates fusion removes), linked by a few shared points.
TEST(FuseWithNeighbours, MergesDuplicatesAndOnlyThem) {
  const auto scene = testing::LandmarkScene::Room(3000, 6);
  Vector6d xi;
  xi << 0.12, 0.02, -0.05, 0.01, 0.04, -0.01;
  std::vector<int> lm0, lm1;
  Map map;
  const KeyFrameId k0 = map.AddKeyFrame(scene.MakeFrame(SE3d(), 0, 1, 0.5, 8, &lm0), SE3d());
  const KeyFrameId k1 = map.AddKeyFrame(scene.MakeFrame(SE3d::Exp(xi), 1, 2, 0.5, 8, &lm1), SE3d::Exp(xi));
  std::map<MapPointId, int> landmark;
  std::map<int, MapPointId> point_in_k0;
  for (std::size_t i = 0; i < lm0.size(); ++i) {
    const MapPointId p = map.AddMapPoint(scene.points[lm0[i]], k0, static_cast<int>(i));
    landmark[p] = lm0[i];
    point_in_k0[lm0[i]] = p;
  }
  int shared = 0, duplicates = 0;
  for (std::size_t i = 0; i < lm1.size(); ++i) {
    const bool in_k0 = point_in_k0.count(lm1[i]) > 0;
    if (in_k0 && shared < 30) {
      ASSERT_TRUE(map.AddObservation(point_in_k0[lm1[i]], k1, static_cast<int>(i)));
      ++shared;
      continue;
    }
    landmark[map.AddMapPoint(scene.points[lm1[i]], k1, static_cast<int>(i))] = lm1[i];
    duplicates += in_k0;
  }
  map.UpdateConnections(k1);
  ASSERT_GT(duplicates, 300);
  const std::size_t before = map.NumMapPoints();

  const FusionStats stats = FuseWithNeighbours(&map, k1);
  EXPECT_EQ(stats.targets, 1);
  const int merged = static_cast<int>(before - map.NumMapPoints());
  EXPECT_LE(merged, duplicates);
  EXPECT_GT(merged, 0.8 * duplicates);
  // No point mixes two landmarks.
  int mixed = 0, checked = 0;
  const auto kf0 = map.GetKeyFrame(k0);
  const auto kf1 = map.GetKeyFrame(k1);
  std::map<MapPointId, int> seen_in_k0;
  for (std::size_t i = 0; i < kf0->points.size(); ++i) {
    if (kf0->points[i] != kNoId) seen_in_k0[kf0->points[i]] = lm0[i];
  }
  for (std::size_t i = 0; i < kf1->points.size(); ++i) {
    const auto it = seen_in_k0.find(kf1->points[i]);
    if (it == seen_in_k0.end()) continue;
    ++checked;
    mixed += it->second != lm1[i];
  }
  EXPECT_GT(checked, shared + 0.8 * duplicates);
  EXPECT_LT(mixed, 0.01 * checked);
}

TEST(FusionOptions, Check) {
  FusionOptions o;
  o.neighbours = -1;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
