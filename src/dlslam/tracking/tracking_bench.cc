// The tracker's local map (Map::GetLocalMap: the keyframes that see one
// frame's matches, their neighbours, and all their points, copied under the
// map's lock) and the search of its points in a frame (SearchByProjection,
// the grid lookups of Frame::FeaturesInArea at its core), on a map made
// without images: a landmark room (tests/support/landmark_scene.h) tracked
// over 120 frames of a smooth path.

#include <benchmark/benchmark.h>

#include <memory>

#include "dlslam/match/projection_matcher.h"
#include "dlslam/tracking/tracker.h"
#include "dlslam/util/check.h"
#include "tests/support/landmark_scene.h"

namespace {

using namespace dlslam;
using testing::SmoothRoomPath;


struct Mapped {
  testing::LandmarkScene scene = testing::LandmarkScene::Room(20000, 3);
  Map map;
  std::unique_ptr<Tracker> tracker;
  int frames = 120;
};

Mapped& GetMapped() {
  static Mapped* mapped = [] {
    auto* m = new Mapped;
    TrackerOptions options;
    options.max_frames_between_keyframes = 10;
    m->tracker = std::make_unique<Tracker>(options, &m->map);
    for (int i = 0; i < m->frames; ++i) m->tracker->Track(m->scene.MakeFrame(SmoothRoomPath(i), i / 30.0, 100 + i));
    const std::shared_ptr<Frame> last = m->scene.MakeFrame(SmoothRoomPath(m->frames), m->frames / 30.0, 99);
    const TrackingResult r = m->tracker->Track(last);
    DLSLAM_CHECK(r.state == TrackingState::kOk, "the benchmark's map did not track");
    return m;
  }();
  return *mapped;
}

void BM_GetLocalMap(benchmark::State& state) {
  Mapped& m = GetMapped();
  // The points one frame matches: those of the newest keyframes.
  std::vector<MapPointId> matched;
  for (const MapPointView& p : m.map.GetLocalMap(m.map.GetKeyFrame(m.tracker->reference_keyframe())->points, 3).points) {
    matched.push_back(p.id);
    if (matched.size() >= 400) break;
  }
  std::size_t points = 0;
  for (auto _ : state) {
    const LocalMapSnapshot snap = m.map.GetLocalMap(matched, 40);
    points = snap.points.size();
    benchmark::DoNotOptimize(snap.points.data());
  }
  state.counters["keyframes_in_map"] = static_cast<double>(m.map.NumKeyFrames());
  state.counters["points_returned"] = static_cast<double>(points);
}
BENCHMARK(BM_GetLocalMap)->Unit(benchmark::kMicrosecond);

void BM_SearchLocalMapByProjection(benchmark::State& state) {
  Mapped& m = GetMapped();
  const SE3d pose = SmoothRoomPath(m.frames + 1);
  const std::shared_ptr<Frame> frame = m.scene.MakeFrame(pose, (m.frames + 1) / 30.0, 98);
  std::vector<MapPointId> seen;
  for (const MapPointView& p : m.map.GetLocalMap(m.map.GetKeyFrame(m.tracker->reference_keyframe())->points, 3).points) {
    seen.push_back(p.id);
    if (seen.size() >= 400) break;
  }
  const LocalMapSnapshot local = m.map.GetLocalMap(seen, 40);
  std::vector<MapPointId> matches;
  int matched = 0;
  for (auto _ : state) {
    matches.clear();
    matched = SearchByProjection(*frame, pose, local.points, ProjectionMatchOptions{}, &matches).matched;
    benchmark::DoNotOptimize(matches.data());
  }
  state.counters["points"] = static_cast<double>(local.points.size());
  state.counters["keypoints"] = static_cast<double>(frame->size());
  state.counters["matched"] = matched;
}
BENCHMARK(BM_SearchLocalMapByProjection)->Unit(benchmark::kMicrosecond);

}  // namespace
