#include "dlslam/map/map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

SE3d Pose(double x, double yaw) {
  Vector6d xi;
  xi << x, 0, 0, 0, yaw, 0;
  return SE3d::Exp(xi);
}

TEST(Map, PointsObservationsAndCovisibility) {
  const auto scene = testing::LandmarkScene::Room(2000, 1);
  Map map;
  std::vector<int> lm0, lm1;
  auto f0 = scene.MakeFrame(Pose(0, 0), 0.0, 1, 0, 0, &lm0);
  auto f1 = scene.MakeFrame(Pose(-0.1, 0.02), 0.1, 2, 0, 0, &lm1);
  const KeyFrameId k0 = map.AddKeyFrame(f0, Pose(0, 0));
  const KeyFrameId k1 = map.AddKeyFrame(f1, Pose(-0.1, 0.02));
  std::map<int, MapPointId> point_of_landmark;
  std::map<int, int> weight_of_landmark;  // observations, one with depth counting twice
  const auto weight = [](const Frame& f, std::size_t i) { return f.keypoint(i).right_u >= 0 ? 2 : 1; };
  for (std::size_t i = 0; i < lm0.size(); ++i) {
    point_of_landmark[lm0[i]] = map.AddMapPoint(scene.points[lm0[i]], k0, static_cast<int>(i));
    weight_of_landmark[lm0[i]] = weight(*f0, i);
  }
  int shared = 0;
  for (std::size_t i = 0; i < lm1.size(); ++i) {
    const auto it = point_of_landmark.find(lm1[i]);
    if (it == point_of_landmark.end()) continue;
    EXPECT_TRUE(map.AddObservation(it->second, k1, static_cast<int>(i)));
    EXPECT_FALSE(map.AddObservation(it->second, k1, static_cast<int>(i)));  // twice: refused
    weight_of_landmark[lm1[i]] += weight(*f1, i);
    ++shared;
  }
  int weight3 = 0, weight2 = 0;
  for (const auto& [lm, w] : weight_of_landmark) {
    weight3 += w >= 3;
    weight2 += w >= 2;
  }
  ASSERT_GT(shared, 100);
  map.UpdateConnections(k1);
  EXPECT_EQ(map.NumKeyFrames(), 2u);
  EXPECT_EQ(map.NumMapPoints(), lm0.size());
  // Observations with depth count twice (nearly every keypoint has depth:
  // shared points have 4, the others 2).
  EXPECT_EQ(map.TrackedPoints(k0, 3), weight3);
  EXPECT_EQ(map.TrackedPoints(k0, 2), weight2);
  EXPECT_GT(weight3, 0.95 * shared);
  EXPECT_LE(weight3, shared);
  EXPECT_GT(weight2, 0.95 * static_cast<double>(lm0.size()));
  EXPECT_EQ(map.TrackedPoints(k1, 1), shared);

  // The local map of points seen in k1 holds both keyframes, k1 first.
  std::vector<MapPointId> seen;
  for (const auto& [lm, id] : point_of_landmark) seen.push_back(id);
  const LocalMapSnapshot local = map.GetLocalMap(seen);
  EXPECT_EQ(local.keyframes.size(), 2u);
  EXPECT_EQ(local.points.size(), lm0.size());

  // A point's normal points from the cameras to it; its distance range covers them.
  const auto views = map.GetPoints({point_of_landmark.begin()->second});
  ASSERT_EQ(views.size(), 1u);
  const Eigen::Vector3d ray = (views[0].position - Pose(0, 0).Inverse().translation()).normalized();
  EXPECT_GT(views[0].normal.dot(ray), 0.99);
  const double d = (views[0].position - Pose(0, 0).Inverse().translation()).norm();
  EXPECT_LE(views[0].min_distance, d);
  EXPECT_GE(views[0].max_distance, d * 0.999);
}

// Five keyframes at one pose, all seeing the same points: each one is
// redundant. Culling around keyframe 2 may remove the older keyframe 1 but
// never keyframe 0, 2 itself, or 3 and 4, which local mapping has not
// processed yet (in the threaded system tracking may still be inserting them).
TEST(Map, CullingSparesKeyFramesNotYetLocallyMapped) {
  const auto scene = testing::LandmarkScene::Room(1500, 3);
  Map map;
  std::map<int, MapPointId> point_of_landmark;
  for (int k = 0; k < 5; ++k) {
    std::vector<int> landmarks;
    const KeyFrameId id =
        map.AddKeyFrame(scene.MakeFrame(Pose(0, 0), 0.1 * k, 10 + k, 0, 0, &landmarks), Pose(0, 0));
    ASSERT_EQ(id, static_cast<KeyFrameId>(k));
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const auto it = point_of_landmark.find(landmarks[i]);
      if (it == point_of_landmark.end()) {
        point_of_landmark[landmarks[i]] = map.AddMapPoint(scene.points[landmarks[i]], id, static_cast<int>(i));
      } else {
        ASSERT_TRUE(map.AddObservation(it->second, id, static_cast<int>(i)));
      }
    }
    map.UpdateConnections(id);
  }
  ASSERT_GT(point_of_landmark.size(), 100u);
  const std::vector<KeyFrameId> culled = map.CullRedundantKeyFrames(2, /*close_depth=*/10.0);
  EXPECT_EQ(culled, std::vector<KeyFrameId>{1});
  std::vector<KeyFrameId> left;
  for (const KeyFramePose& k : map.KeyFramePoses()) left.push_back(k.id);
  EXPECT_EQ(left, (std::vector<KeyFrameId>{0, 2, 3, 4}));
}

// Three keyframes along a line: k0 and k2 share points with k1, k0 more
// than k2 (k2 looks further along). Returns their ids and the points.
struct ThreeKeyFrames {
  KeyFrameId k0, k1, k2;
  std::vector<MapPointId> points;
};

ThreeKeyFrames MakeThreeKeyFrames(Map& map, const testing::LandmarkScene& scene) {
  ThreeKeyFrames out;
  std::map<int, MapPointId> point_of_landmark;
  const double x[3] = {0.0, -0.1, -0.3};
  const double yaw[3] = {0.0, 0.05, 0.4};
  KeyFrameId ids[3];
  for (int k = 0; k < 3; ++k) {
    std::vector<int> landmarks;
    auto frame = scene.MakeFrame(Pose(x[k], yaw[k]), k * 0.1, 10 + k, 0, 0, &landmarks);
    ids[k] = map.AddKeyFrame(frame, Pose(x[k], yaw[k]));
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const auto it = point_of_landmark.find(landmarks[i]);
      if (it != point_of_landmark.end()) {
        map.AddObservation(it->second, ids[k], static_cast<int>(i));
      } else {
        point_of_landmark[landmarks[i]] = map.AddMapPoint(scene.points[landmarks[i]], ids[k], static_cast<int>(i));
      }
    }
    map.UpdateConnections(ids[k]);
  }
  for (const auto& [lm, id] : point_of_landmark) out.points.push_back(id);
  out.k0 = ids[0];
  out.k1 = ids[1];
  out.k2 = ids[2];
  return out;
}

TEST(Map, CovisibleKeyFramesBestFirst) {
  const auto scene = testing::LandmarkScene::Room(3000, 2);
  Map map;
  EXPECT_TRUE(map.GetCovisibleKeyFrames(0, 5).empty());
  const ThreeKeyFrames kfs = MakeThreeKeyFrames(map, scene);
  const auto views = map.GetCovisibleKeyFrames(kfs.k1, 5);
  ASSERT_EQ(views.size(), 3u);
  EXPECT_EQ(views[0].id, kfs.k1);
  EXPECT_EQ(views[1].id, kfs.k0);  // the closer view shares more points
  EXPECT_EQ(views[2].id, kfs.k2);
  EXPECT_EQ(views[0].points.size(), views[0].frame->size());
  EXPECT_TRUE(views[1].cam_from_world.translation().isApprox(Pose(0, 0).translation()));
  EXPECT_EQ(map.GetCovisibleKeyFrames(kfs.k1, 2).size(), 2u);
  // An unknown keyframe: start from the newest.
  EXPECT_EQ(map.GetCovisibleKeyFrames(12345, 1).front().id, kfs.k2);
}

TEST(Map, ErasePointsUnlinksThemFromTheirKeyFrames) {
  const auto scene = testing::LandmarkScene::Room(3000, 3);
  Map map;
  const ThreeKeyFrames kfs = MakeThreeKeyFrames(map, scene);
  const std::size_t before = map.NumMapPoints();
  const std::vector<MapPointId> doomed(kfs.points.begin(), kfs.points.begin() + 10);
  std::vector<MapPointId> with_unknown = doomed;
  with_unknown.push_back(kNoId - 1);
  EXPECT_EQ(map.ErasePoints(with_unknown), 10);
  EXPECT_EQ(map.ErasePoints(doomed), 0);  // already gone
  EXPECT_EQ(map.NumMapPoints(), before - 10);
  EXPECT_TRUE(map.GetPoints(doomed).empty());
  for (KeyFrameId k : {kfs.k0, kfs.k1, kfs.k2}) {
    const std::optional<KeyFrameSnapshot> kf = map.GetKeyFrame(k);
    ASSERT_TRUE(kf.has_value());
    for (MapPointId id : kf->points) {
      EXPECT_EQ(std::count(doomed.begin(), doomed.end(), id), 0) << "keyframe " << k;
    }
  }
}

TEST(Map, PredictOctave) {
  ScalePyramid p;
  EXPECT_EQ(PredictOctave(2.0, 2.0, p), 0);
  EXPECT_EQ(PredictOctave(2.0 / 1.2, 2.0, p), 1);
  EXPECT_EQ(PredictOctave(0.01, 2.0, p), p.levels - 1);
  EXPECT_EQ(PredictOctave(5.0, 2.0, p), 0);
}

TEST(Map, HammingDistanceOfDescriptors) {
  Descriptor a{}, b{};
  EXPECT_EQ(HammingDistance(a.data(), b.data()), 0);
  b[0] = 0xFF;
  b[31] = 0x01;
  EXPECT_EQ(HammingDistance(a.data(), b.data()), 9);
}

}  // namespace
}  // namespace dlslam
