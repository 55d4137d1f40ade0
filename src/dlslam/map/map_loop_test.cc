#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

#include "dlslam/map/map.h"
#include "dlslam/optimize/bundle_adjuster.h"
#include "tests/support/landmark_scene.h"

namespace dlslam {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Kind = EssentialGraph::Edge::Kind;

SE3d Pose(double x, double y, double z, double yaw) {
  Vector6d xi;
  xi << x, y, z, 0, yaw, 0;
  return SE3d::Exp(xi);
}

double PoseDistance(const SE3d& a, const SE3d& b) { return (a * b.Inverse()).Log().norm(); }

// A chain of five keyframes with hand-picked sharing (keypoint i of every
// keyframe is the same landmark). Points on keypoints:
//   [0,150) made by k0, seen by k0 k1 k2    [150,200) made by k1, seen by k1 k2 k3
//   [200,230) made by k2, seen by k2 k3     [230,260) made by k3, seen by k3 k4
// Connections are updated as each keyframe comes, so the parents are
// k1->k0, k2->k1 (200 shared beat 150), k3->k2 (80 beat 50), k4->k3; shared
// points: 01:150 02:150 12:200 13:50 23:80 34:30.
struct Chain {
  testing::LandmarkScene scene = testing::LandmarkScene::Room(3000, 5);
  Map map;
  std::vector<int> lm;
  std::vector<SE3d> poses = {Pose(0, 0, 0, 0), Pose(0.3, 0, 0, 0.1), Pose(0.6, 0.1, 0, 0.2),
                             Pose(0.9, 0.1, 0.2, 0.3), Pose(1.2, 0, 0.3, 0.4)};
  KeyFrameId k[5];
  std::vector<MapPointId> point;  // per keypoint

  Chain() {
    const auto frame = scene.MakeFrame(SE3d(), 0.0, 1, 0, 0, &lm);
    EXPECT_GE(frame->size(), 260u);
    point.assign(260, kNoId);
    const int made_by[5][2] = {{0, 150}, {150, 200}, {200, 230}, {230, 260}, {0, 0}};
    const int seen[5][2] = {{0, 0}, {0, 150}, {0, 200}, {150, 230}, {230, 260}};
    for (int i = 0; i < 5; ++i) {
      k[i] = map.AddKeyFrame(frame, poses[i]);
      for (int j = seen[i][0]; j < seen[i][1]; ++j) EXPECT_TRUE(map.AddObservation(point[j], k[i], j));
      for (int j = made_by[i][0]; j < made_by[i][1]; ++j) point[j] = map.AddMapPoint(scene.points[lm[j]], k[i], j);
      map.UpdateConnections(k[i]);
    }
  }
  Eigen::Vector3d Position(int keypoint) const { return map.GetPoints({point[keypoint]}).at(0).position; }
};

std::map<std::pair<KeyFrameId, KeyFrameId>, Kind> EdgesById(const EssentialGraph& graph) {
  std::map<std::pair<KeyFrameId, KeyFrameId>, Kind> out;
  for (const auto& e : graph.edges) {
    EXPECT_LT(e.from, e.to);
    const auto [it, inserted] = out.emplace(std::make_pair(graph.ids[e.from], graph.ids[e.to]), e.kind);
    EXPECT_TRUE(inserted) << "pair listed twice";
  }
  return out;
}

TEST(MapLoop, EssentialGraphHasTreeCovisibilityAndLoopEdges) {
  Chain c;
  const EssentialGraph before = c.map.GetEssentialGraph(100);
  ASSERT_EQ(before.ids, (std::vector<KeyFrameId>{0, 1, 2, 3, 4}));
  using Edges = std::map<std::pair<KeyFrameId, KeyFrameId>, Kind>;
  EXPECT_EQ(EdgesById(before), (Edges{{{0, 1}, Kind::kTree},
                                      {{0, 2}, Kind::kCovisibility},
                                      {{1, 2}, Kind::kTree},
                                      {{2, 3}, Kind::kTree},
                                      {{3, 4}, Kind::kTree}}));
  // A lower threshold admits the 50-point pair 1-3.
  EXPECT_EQ(EdgesById(c.map.GetEssentialGraph(50)).count({1, 3}), 1u);
  EXPECT_EQ(EdgesById(c.map.GetEssentialGraph(51)).count({1, 3}), 0u);

  c.map.AddLoopEdge(4, 0);
  c.map.AddLoopEdge(2, 0);  // also a covisibility edge: listed once, as the loop
  c.map.AddLoopEdge(3, 3);  // ignored
  c.map.AddLoopEdge(3, 99);  // ignored: no such keyframe
  const EssentialGraph after = c.map.GetEssentialGraph(100);
  EXPECT_EQ(EdgesById(after), (Edges{{{0, 1}, Kind::kTree},
                                     {{0, 2}, Kind::kLoop},
                                     {{0, 4}, Kind::kLoop},
                                     {{1, 2}, Kind::kTree},
                                     {{2, 3}, Kind::kTree},
                                     {{3, 4}, Kind::kTree}}));
  // Measurements from the current poses: to_from_from carries from onto to.
  for (const auto& e : after.edges) {
    EXPECT_TRUE(after.cam_from_world[e.from].translation().isApprox(c.poses[after.ids[e.from]].translation()));
    EXPECT_LT(PoseDistance(e.to_from_from * c.poses[after.ids[e.from]], c.poses[after.ids[e.to]]), 1e-12);
  }
}

TEST(MapLoop, CorrectedPosesCarryPointsAndNewerKeyFrames) {
  Chain c;
  const Eigen::Vector3d p0 = c.Position(0), p150 = c.Position(150), p200 = c.Position(200), p230 = c.Position(230);
  const std::uint64_t generation = c.map.Generation();
  // Correct k1 and k2; k3 and k4 are newer than both: they follow k2 (k3's
  // parent) rigidly; k0 is older and stays.
  const SE3d new1 = Pose(0.25, -0.05, 0.02, 0.05);
  const SE3d new2 = Pose(0.5, 0.0, 0.1, 0.1);
  EXPECT_EQ(c.map.ApplyCorrectedPoses({{c.k[1], new1}, {c.k[2], new2}}), 4);
  EXPECT_EQ(c.map.Generation(), generation + 1);
  std::vector<SE3d> now;
  for (const KeyFramePose& kp : c.map.KeyFramePoses()) now.push_back(kp.cam_from_world);
  ASSERT_EQ(now.size(), 5u);
  EXPECT_LT(PoseDistance(now[0], c.poses[0]), 1e-12);
  EXPECT_LT(PoseDistance(now[1], new1), 1e-12);
  EXPECT_LT(PoseDistance(now[2], new2), 1e-12);
  // Relative poses along the moved part of the tree are preserved.
  EXPECT_LT(PoseDistance(now[3] * now[2].Inverse(), c.poses[3] * c.poses[2].Inverse()), 1e-12);
  EXPECT_LT(PoseDistance(now[4] * now[3].Inverse(), c.poses[4] * c.poses[3].Inverse()), 1e-12);
  // Each point keeps its coordinates in its reference keyframe's camera.
  EXPECT_TRUE(c.Position(0).isApprox(p0, 1e-15));  // reference k0 did not move
  EXPECT_LT((now[1] * c.Position(150) - c.poses[1] * p150).norm(), 1e-12);
  EXPECT_LT((now[2] * c.Position(200) - c.poses[2] * p200).norm(), 1e-12);
  EXPECT_LT((now[3] * c.Position(230) - c.poses[3] * p230).norm(), 1e-12);
  EXPECT_GT((c.Position(150) - p150).norm(), 0.01);  // it did move
}

TEST(MapLoop, OlderKeyFramesOutsideTheCorrectionStay) {
  Chain c;
  // Only k3 corrected: k4 follows, k0..k2 (older) stay, and so do their points.
  const SE3d new3 = Pose(1.0, 0.2, 0.1, 0.35);
  const Eigen::Vector3d p150 = c.Position(150);
  EXPECT_EQ(c.map.ApplyCorrectedPoses({{c.k[3], new3}, {12345, SE3d()}}), 2);
  const auto now = c.map.KeyFramePoses();
  for (int i = 0; i < 3; ++i) EXPECT_LT(PoseDistance(now[i].cam_from_world, c.poses[i]), 1e-12);
  EXPECT_LT(PoseDistance(now[4].cam_from_world * new3.Inverse(), c.poses[4] * c.poses[3].Inverse()), 1e-12);
  EXPECT_TRUE(c.Position(150).isApprox(p150, 1e-15));
  // Nothing known to correct: nothing moves, no new generation.
  const std::uint64_t generation = c.map.Generation();
  EXPECT_EQ(c.map.ApplyCorrectedPoses({{777, SE3d()}}), 0);
  EXPECT_EQ(c.map.Generation(), generation);
}

TEST(MapLoop, ReplacePointMovesObservations) {
  Chain c;
  // Keypoint 150's point is seen by k1 k2 k3, keypoint 0's by k0 k1 k2:
  // merging 150 into 0 keeps k1's and k2's view of 0 (they see it already)
  // and gives k3's keypoint 150 to point 0.
  const MapPointId from = c.point[150], into = c.point[0];
  EXPECT_FALSE(c.map.ReplacePoint(into, into));
  EXPECT_TRUE(c.map.ReplacePoint(from, into));
  EXPECT_TRUE(c.map.GetPoints({from}).empty());
  EXPECT_EQ(c.map.GetKeyFrame(c.k[3])->points[150], into);
  EXPECT_EQ(c.map.GetKeyFrame(c.k[1])->points[150], kNoId);
  EXPECT_EQ(c.map.GetKeyFrame(c.k[1])->points[0], into);
  EXPECT_FALSE(c.map.ReplacePoint(from, into));  // gone
  EXPECT_FALSE(c.map.ReplacePoint(into, 987654));
}

// Five keyframes at one pose seeing the same points: culling around k2
// removes k1 (map_test) unless k1 anchors a loop.
void MakeRedundantKeyFrames(Map& map, const testing::LandmarkScene& scene) {
  std::map<int, MapPointId> point_of_landmark;
  for (int k = 0; k < 5; ++k) {
    std::vector<int> landmarks;
    const KeyFrameId id = map.AddKeyFrame(scene.MakeFrame(SE3d(), 0.1 * k, 10 + k, 0, 0, &landmarks), SE3d());
    for (std::size_t i = 0; i < landmarks.size(); ++i) {
      const auto it = point_of_landmark.find(landmarks[i]);
      if (it == point_of_landmark.end()) {
        point_of_landmark[landmarks[i]] = map.AddMapPoint(scene.points[landmarks[i]], id, static_cast<int>(i));
      } else {
        map.AddObservation(it->second, id, static_cast<int>(i));
      }
    }
    map.UpdateConnections(id);
  }
}

TEST(MapLoop, LoopAnchorsAreNotCulled) {
  const auto scene = testing::LandmarkScene::Room(1500, 3);
  Map anchored;
  MakeRedundantKeyFrames(anchored, scene);
  anchored.AddLoopEdge(1, 4);
  EXPECT_TRUE(anchored.CullRedundantKeyFrames(2, /*close_depth=*/10.0).empty());
  EXPECT_EQ(anchored.NumKeyFrames(), 5u);

  // The control: without the loop edge k1 goes; it stays reachable through
  // its parent k0, and follows it when k0 is corrected.
  Map plain;
  MakeRedundantKeyFrames(plain, scene);
  EXPECT_EQ(plain.CullRedundantKeyFrames(2, 10.0), std::vector<KeyFrameId>{1});
  plain.UpdateConnections(1);  // gone: a no-op
  const SE3d new0 = Pose(0.1, 0.0, -0.1, 0.05);
  EXPECT_EQ(plain.ApplyCorrectedPoses({{0, new0}}), 4);  // k0 and its newer descendants k2 k3 k4
  EXPECT_LT(PoseDistance(*plain.ResolveCamFromWorld(1), new0), 1e-12);  // same pose as k0 before
}

// A new map's first keyframe (an anchor) holds its map in place like
// keyframe 0: fixed in local and global bundles, never culled; the keyframes
// after it belong to its map until it is merged (ClearAnchor).
TEST(MapLoop, AnchorsHoldTheirMapsUntilMerged) {
  const auto scene = testing::LandmarkScene::Room(1500, 3);
  Map map;
  MakeRedundantKeyFrames(map, scene);  // k0..k4; k1 is redundant
  EXPECT_TRUE(map.IsAnchor(0));
  EXPECT_FALSE(map.IsAnchor(1));
  EXPECT_EQ(map.MapOrigin(4), 0u);
  map.SetAnchor(1);
  EXPECT_TRUE(map.IsAnchor(1));
  EXPECT_EQ(map.MapOrigin(0), 0u);
  EXPECT_EQ(map.MapOrigin(1), 1u);
  EXPECT_EQ(map.MapOrigin(4), 1u);
  EXPECT_TRUE(map.CullRedundantKeyFrames(2, /*close_depth=*/10.0).empty());
  const auto fixed_in = [](const LocalBundle& bundle, KeyFrameId id) {
    const auto it = std::find(bundle.pose_ids.begin(), bundle.pose_ids.end(), id);
    EXPECT_NE(it, bundle.pose_ids.end()) << "keyframe " << id << " not in the bundle";
    return it != bundle.pose_ids.end() && bundle.problem.poses[it - bundle.pose_ids.begin()].fixed;
  };
  const LocalBundle local = map.BuildLocalBundle(2);
  EXPECT_TRUE(fixed_in(local, 1));
  EXPECT_FALSE(fixed_in(local, 2));
  const LocalBundle global = map.BuildGlobalBundle();
  EXPECT_TRUE(fixed_in(global, 0));
  EXPECT_TRUE(fixed_in(global, 1));
  EXPECT_FALSE(fixed_in(global, 3));

  map.ClearAnchor(1);
  EXPECT_FALSE(map.IsAnchor(1));
  EXPECT_EQ(map.MapOrigin(4), 0u);
  EXPECT_FALSE(fixed_in(map.BuildLocalBundle(2), 1));
  map.ClearAnchor(0);  // keyframe 0 always anchors the first map
  EXPECT_TRUE(map.IsAnchor(0));
  EXPECT_EQ(map.CullRedundantKeyFrames(2, 10.0), std::vector<KeyFrameId>{1});
}

// Three keyframes along a path seeing a landmark scene with exact pixels and
// depth; keyframes 1 and 2 are inserted at wrong poses.
struct SceneMap {
  testing::LandmarkScene scene = testing::LandmarkScene::Room(1500, 7);
  Map map;
  std::vector<SE3d> truth = {Pose(0, 0, 0, 0), Pose(-0.15, 0.02, 0.05, 0.08), Pose(-0.3, 0.0, 0.1, 0.16)};
  std::vector<SE3d> inserted;
  std::map<int, MapPointId> point_of_landmark;

  explicit SceneMap(const std::vector<SE3d>& error) {
    for (int k = 0; k < 3; ++k) {
      std::vector<int> landmarks;
      inserted.push_back(error[k] * truth[k]);
      const KeyFrameId id = map.AddKeyFrame(scene.MakeFrame(truth[k], 0.1 * k, 20 + k, 0, 0, &landmarks), inserted[k]);
      for (std::size_t i = 0; i < landmarks.size(); ++i) {
        const auto it = point_of_landmark.find(landmarks[i]);
        if (it == point_of_landmark.end()) {
          point_of_landmark[landmarks[i]] = map.AddMapPoint(scene.points[landmarks[i]], id, static_cast<int>(i));
        } else {
          map.AddObservation(it->second, id, static_cast<int>(i));
        }
      }
      map.UpdateConnections(id);
    }
  }
};

// How many keyframes see each point (keyframes 0..count-1).
std::map<MapPointId, int> ViewCounts(const Map& map, KeyFrameId count) {
  std::map<MapPointId, int> views;
  for (KeyFrameId k = 0; k < count; ++k) {
    const std::optional<KeyFrameSnapshot> kf = map.GetKeyFrame(k);
    for (MapPointId id : kf->points) {
      if (id != kNoId) ++views[id];
    }
  }
  return views;
}

TEST(MapLoop, GlobalBundleRoundTripChangesNothing) {
  SceneMap s({SE3d(), SE3d(), SE3d()});
  const LocalBundle bundle = s.map.BuildGlobalBundle();
  ASSERT_EQ(bundle.pose_ids, (std::vector<KeyFrameId>{0, 1, 2}));
  EXPECT_TRUE(bundle.problem.poses[0].fixed);
  EXPECT_FALSE(bundle.problem.poses[1].fixed);
  EXPECT_FALSE(bundle.problem.poses[2].fixed);
  // Exactly the points with two or more views, with all their observations.
  std::vector<MapPointId> multi, all;
  std::size_t observations = 0;
  for (const auto& [id, views] : ViewCounts(s.map, 3)) {
    all.push_back(id);
    if (views < 2) continue;
    multi.push_back(id);
    observations += views;
  }
  std::vector<MapPointId> in_bundle = bundle.point_ids;
  std::sort(in_bundle.begin(), in_bundle.end());
  EXPECT_EQ(in_bundle, multi);
  EXPECT_EQ(bundle.problem.observations.size(), observations);
  ASSERT_GT(multi.size(), 100u);
  ASSERT_LT(multi.size(), all.size());  // some points have one view

  const auto points_before = s.map.GetPoints(all);
  const std::uint64_t generation = s.map.Generation();
  s.map.ApplyGlobalBundle(bundle, std::vector<bool>(bundle.problem.observations.size(), false));
  EXPECT_EQ(s.map.Generation(), generation + 1);
  const auto points_after = s.map.GetPoints(all);
  ASSERT_EQ(points_after.size(), points_before.size());
  for (std::size_t j = 0; j < points_before.size(); ++j) EXPECT_EQ(points_after[j].position, points_before[j].position);
  const auto poses = s.map.KeyFramePoses();
  for (int k = 0; k < 3; ++k) EXPECT_EQ(poses[k].cam_from_world.matrix(), s.truth[k].matrix());
}

TEST(MapLoop, GlobalBundleFixesPerturbedPosesAndCarriesNewcomers) {
  SceneMap s({SE3d(), Pose(0.03, -0.02, 0.02, 0.02), Pose(-0.04, 0.03, -0.02, -0.03)});
  LocalBundle bundle = s.map.BuildGlobalBundle();
  // Meanwhile tracking adds keyframe 3 (child of 2, 5 cm beside it).
  std::vector<int> landmarks;
  const SE3d cam3_from_cam2 = Pose(0.05, 0, 0, 0);
  const KeyFrameId k3 = s.map.AddKeyFrame(s.scene.MakeFrame(cam3_from_cam2 * s.truth[2], 0.3, 23, 0, 0, &landmarks),
                                          cam3_from_cam2 * s.inserted[2]);
  int added = 0;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const auto it = s.point_of_landmark.find(landmarks[i]);
    if (it != s.point_of_landmark.end()) added += s.map.AddObservation(it->second, k3, static_cast<int>(i));
  }
  ASSERT_GT(added, 50);
  s.map.UpdateConnections(k3);
  const EssentialGraph graph = s.map.GetEssentialGraph(1);
  ASSERT_TRUE(std::any_of(graph.edges.begin(), graph.edges.end(), [](const EssentialGraph::Edge& e) {
    return e.from == 2 && e.to == 3 && e.kind == Kind::kTree;
  }));
  // A point that only keyframe 2 saw when the bundle was built: it moves
  // rigidly with keyframe 2.
  const std::map<MapPointId, int> views = ViewCounts(s.map, 3);
  MapPointId single = kNoId;
  const std::optional<KeyFrameSnapshot> kf2 = s.map.GetKeyFrame(2);
  for (MapPointId id : kf2->points) {
    if (id != kNoId && views.at(id) == 1) single = id;
  }
  ASSERT_NE(single, kNoId);
  const Eigen::Vector3d single_in_cam2 = s.inserted[2] * s.map.GetPoints({single}).at(0).position;

  const BundleSummary summary = SolveBundle(&bundle.problem);
  // Exact pixels, but two landmarks that round to one depth pixel share a
  // depth: those few observations are true outliers.
  EXPECT_LE(summary.outliers, static_cast<int>(bundle.problem.observations.size() / 100));
  s.map.ApplyGlobalBundle(bundle, summary.outlier);
  const auto poses = s.map.KeyFramePoses();
  ASSERT_EQ(poses.size(), 4u);
  for (int k = 0; k < 3; ++k) EXPECT_LT(PoseDistance(poses[k].cam_from_world, s.truth[k]), 1e-5) << "keyframe " << k;
  // The newcomer kept its pose relative to its parent, so it is right too.
  EXPECT_LT(PoseDistance(poses[3].cam_from_world, cam3_from_cam2 * s.truth[2]), 1e-5);
  for (const auto& [lm, id] : s.point_of_landmark) {
    if (views.at(id) >= 2) {
      EXPECT_LT((s.map.GetPoints({id}).at(0).position - s.scene.points[lm]).norm(), 1e-4);
    }
  }
  EXPECT_LT((poses[2].cam_from_world * s.map.GetPoints({single}).at(0).position - single_in_cam2).norm(), 1e-12);
}

}  // namespace
}  // namespace dlslam
