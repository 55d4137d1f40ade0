#include "dlslam/match/fuse_matcher.h"

#include <gtest/gtest.h>

#include <map>

#include "dlslam/map/map.h"
#include "dlslam/util/check.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

TEST(SearchForFusion, FindsTheKeypointOfEachProjectedPoint) {
  const auto scene = testing::LandmarkScene::Room(3000, 5);
  Vector6d xi;
  xi << 0.1, -0.02, 0.05, 0.01, -0.03, 0.01;
  std::vector<int> lm0, lm1;
  Map map;
  const KeyFrameId k0 = map.AddKeyFrame(scene.MakeFrame(SE3d(), 0, 1, 0.5, 8, &lm0), SE3d());
  const auto f1 = scene.MakeFrame(SE3d::Exp(xi), 1, 2, 0.5, 8, &lm1);
  std::map<MapPointId, int> landmark;
  std::vector<MapPointId> ids;
  for (std::size_t i = 0; i < lm0.size(); ++i) {
    ids.push_back(map.AddMapPoint(scene.points[lm0[i]], k0, static_cast<int>(i)));
    landmark[ids.back()] = lm0[i];
  }
  const std::vector<MapPointView> points = map.GetPoints(ids);
  const std::vector<MapPointId> free_keypoints(f1->size(), kNoId);
  const auto found = SearchForFusion(*f1, SE3d::Exp(xi), free_keypoints, points);
  int right = 0;
  for (const FuseCandidate& c : found) right += landmark.at(c.point) == lm1[c.keypoint];
  EXPECT_GT(found.size(), 0.7 * lm1.size());
  EXPECT_GT(right, 0.98 * static_cast<double>(found.size()));

  // Points the keyframe already sees are not candidates.
  std::vector<MapPointId> seen(f1->size(), kNoId);
  for (const FuseCandidate& c : found) seen[c.keypoint] = c.point;
  EXPECT_TRUE(SearchForFusion(*f1, SE3d::Exp(xi), seen, points).empty());
}

TEST(FuseMatchOptions, Check) {
  FuseMatchOptions o;
  o.radius = 0;
  EXPECT_THROW(o.Check(), Error);
}

}  // namespace
}  // namespace dlslam
