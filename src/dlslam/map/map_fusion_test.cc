#include <gtest/gtest.h>

#include "dlslam/map/map.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

// Three keyframes of the same view; keypoint i sees landmark lm[i] in each
// (MakeFrame with the same seed gives the same keypoint order).
struct ThreeViews {
  testing::LandmarkScene scene = testing::LandmarkScene::Room(500, 3);
  Map map;
  std::vector<int> lm;
  KeyFrameId k[3];
  ThreeViews() {
    for (int i = 0; i < 3; ++i) k[i] = map.AddKeyFrame(scene.MakeFrame(SE3d(), i, 1, 0, 0, &lm), SE3d());
  }
};

TEST(MapFusion, FuseAddsAnObservationToAFreeKeypoint) {
  ThreeViews v;
  const MapPointId p = v.map.AddMapPoint(v.scene.points[v.lm[0]], v.k[0], 0);
  EXPECT_TRUE(v.map.FusePoint(p, v.k[1], 0));
  EXPECT_FALSE(v.map.FusePoint(p, v.k[1], 0));  // already seen by k1
  EXPECT_EQ(v.map.GetKeyFrame(v.k[1])->points[0], p);
  EXPECT_EQ(v.map.NumMapPoints(), 1u);
}

TEST(MapFusion, DuplicatesMergeIntoTheBetterObservedPoint) {
  ThreeViews v;
  // p: seen by k0 and k1; q (a duplicate of the same landmark): seen by k2.
  const MapPointId p = v.map.AddMapPoint(v.scene.points[v.lm[0]], v.k[0], 0);
  ASSERT_TRUE(v.map.AddObservation(p, v.k[1], 0));
  const MapPointId q = v.map.AddMapPoint(v.scene.points[v.lm[0]], v.k[2], 0);
  // q projected into k0 lands on p's keypoint: q goes, p takes k2's observation.
  EXPECT_TRUE(v.map.FusePoint(q, v.k[0], 0));
  EXPECT_EQ(v.map.NumMapPoints(), 1u);
  EXPECT_TRUE(v.map.GetPoints({q}).empty());
  for (KeyFrameId kf : v.k) EXPECT_EQ(v.map.GetKeyFrame(kf)->points[0], p);
}

TEST(MapFusion, MergeDropsASecondObservationInTheSameKeyFrame) {
  ThreeViews v;
  const MapPointId p = v.map.AddMapPoint(v.scene.points[v.lm[0]], v.k[0], 0);
  ASSERT_TRUE(v.map.AddObservation(p, v.k[1], 0));
  // q (as many views as p) is seen by k0 at another keypoint and by k2.
  const MapPointId q = v.map.AddMapPoint(v.scene.points[v.lm[1]], v.k[0], 1);
  ASSERT_TRUE(v.map.AddObservation(q, v.k[2], 1));
  // q onto p's keypoint in k1: on a tie the existing point p stays; k0 would
  // see p twice, so q's keypoint there is freed; k2's observation moves to p.
  EXPECT_TRUE(v.map.FusePoint(q, v.k[1], 0));
  EXPECT_TRUE(v.map.GetPoints({q}).empty());
  EXPECT_EQ(v.map.GetKeyFrame(v.k[0])->points[0], p);
  EXPECT_EQ(v.map.GetKeyFrame(v.k[0])->points[1], kNoId);
  EXPECT_EQ(v.map.GetKeyFrame(v.k[1])->points[0], p);
  EXPECT_EQ(v.map.GetKeyFrame(v.k[2])->points[1], p);
  EXPECT_EQ(v.map.NumMapPoints(), 1u);
}

TEST(MapFusion, TriangulatedPointIsSeenByBothKeyFrames) {
  ThreeViews v;
  const MapPointId p = v.map.AddTriangulatedPoint(v.scene.points[v.lm[2]], v.k[0], 2, v.k[1], 2);
  ASSERT_NE(p, kNoId);
  EXPECT_EQ(v.map.GetKeyFrame(v.k[0])->points[2], p);
  EXPECT_EQ(v.map.GetKeyFrame(v.k[1])->points[2], p);
  // A taken keypoint refuses a second point.
  EXPECT_EQ(v.map.AddTriangulatedPoint(v.scene.points[v.lm[2]], v.k[2], 2, v.k[1], 2), kNoId);
  EXPECT_EQ(v.map.NumMapPoints(), 1u);
}

TEST(MapFusion, BestCovisibleRanksAndRespectsTheIdLimit) {
  ThreeViews v;
  for (int i = 0; i < 40; ++i) {
    const MapPointId p = v.map.AddMapPoint(v.scene.points[v.lm[i]], v.k[0], i);
    ASSERT_TRUE(v.map.AddObservation(p, v.k[1], i));
    if (i < 20) {
      ASSERT_TRUE(v.map.AddObservation(p, v.k[2], i));
    }
  }
  v.map.UpdateConnections(v.k[0]);
  EXPECT_EQ(v.map.BestCovisible(v.k[0], 5), (std::vector<KeyFrameId>{v.k[1], v.k[2]}));
  EXPECT_EQ(v.map.BestCovisible(v.k[0], 1), (std::vector<KeyFrameId>{v.k[1]}));
  EXPECT_EQ(v.map.BestCovisible(v.k[2], 5, v.k[0]), (std::vector<KeyFrameId>{v.k[0]}));
}

}  // namespace
}  // namespace dlslam
