#pragma once
// The records the map is made of. They live inside dlslam::Map, behind its
// lock; other threads see copies (views), never references.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "dlslam/data/frame.h"
#include "dlslam/features/matching.h"
#include "dlslam/geometry/se3.h"

namespace dlslam {

using KeyFrameId = std::uint64_t;
using MapPointId = std::uint64_t;
inline constexpr std::uint64_t kNoId = std::numeric_limits<std::uint64_t>::max();

using Descriptor = std::array<std::uint8_t, 32>;  // 256-bit ORB descriptor

Descriptor DescriptorOf(const Frame& frame, std::size_t keypoint);

// Hamming distance between two 256-bit descriptors.
using features::HammingDistance;

struct MapPoint {
  MapPointId id = kNoId;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world [m]
  Descriptor descriptor{};  // the observation's descriptor closest to all others
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // mean viewing direction (unit)
  // Distances [m] at which the point can be matched across the pyramid.
  double min_distance = 0.0;
  double max_distance = 0.0;
  std::map<KeyFrameId, int> observations;  // keyframe -> keypoint index
  KeyFrameId reference_keyframe = kNoId;
  KeyFrameId first_keyframe = kNoId;
  // Culling statistics: frames where it should have been seen / was matched.
  int times_visible = 1;
  int times_found = 1;
};

struct KeyFrame {
  KeyFrameId id = kNoId;
  std::shared_ptr<const Frame> frame;  // keypoints and descriptors (immutable)
  SE3d cam_from_world;
  std::vector<MapPointId> points;          // per keypoint; kNoId if none
  std::map<KeyFrameId, int> covisibility;  // keyframe -> number of shared points
  KeyFrameId parent = kNoId;               // spanning tree
  std::set<KeyFrameId> loop_edges;         // keyframes a loop closure joined it to
};

// A culled keyframe: frames tracked against it keep a pose through its
// parent (Map::ResolveCamFromWorld).
struct CulledKeyFrame {
  KeyFrameId id = kNoId;
  KeyFrameId parent = kNoId;
  SE3d cam_from_parent;
};

// Everything the map holds, sorted by id: what a map file stores
// (map/map_file.h) and Map::Export / Map::Import exchange.
struct MapContents {
  std::vector<KeyFrame> keyframes;
  std::vector<MapPoint> points;
  std::vector<CulledKeyFrame> culled;
  // First keyframes of maps not merged yet (Map::SetAnchor), sorted; keyframe 0 is implied.
  std::vector<KeyFrameId> anchors;
  KeyFrameId next_keyframe_id = 0;
  MapPointId next_point_id = 0;
};

// What tracking needs of a map point, copied out of the map.
struct MapPointView {
  MapPointId id = kNoId;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Descriptor descriptor{};
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double min_distance = 0.0;
  double max_distance = 0.0;
};

// Pyramid level at which a point `distance` metres away is expected to be
// seen, given its max matchable distance (ORB-SLAM's PredictScale).
int PredictOctave(double distance, double max_distance, const ScalePyramid& pyramid);

}  // namespace dlslam
