// A new map after a loss that relocalization cannot end, merged into the old
// one when they meet (issue 14, "never lost": ORB-SLAM3's Atlas idea). Real
// frames: 7-Scenes redkitchen (../shared/data), with the lens covered for
// frames 150-199 while the camera goes on moving (in the semi-real crowd
// sequence people did this). After the gap the view is one the map does not
// hold: without new maps the camera stays lost until it comes back near a
// keyframe; with them it is posed from the first frame after the gap, in a
// map that starts at the last pose, and that map is moved onto the old one
// once two relocalizations in a row agree where it lies. Skipped when the
// shared data is absent.

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "dlslam/eval/ate.h"
#include "dlslam/io/sequence.h"
#include "dlslam/system/slam_system.h"
#include "tests/support/test_data.h"

namespace dlslam {
namespace {

constexpr int kCoveredFrom = 150;
constexpr int kCoveredTo = 200;  // exclusive
constexpr int kFrames = 330;

struct CoveredRun {
  RunStats stats;
  std::vector<FramePoseSource> sources;
  eval::AteResult ate;
};

CoveredRun RunCovered(const std::filesystem::path& folder, int new_map_after_lost_frames, bool sequential = true) {
  const io::RgbdSequence sequence = io::RgbdSequence::Open(folder);
  SystemOptions options;
  options.sequential = sequential;
  options.tracker.new_map_after_lost_frames = new_map_after_lost_frames;
  SlamSystem slam(sequence.camera(), options);
  const int n = std::min<int>(kFrames, static_cast<int>(sequence.size()));
  for (int i = 0; i < n; ++i) {
    io::RgbdFrame f = sequence.LoadFrame(static_cast<std::size_t>(i));
    if (i >= kCoveredFrom && i < kCoveredTo) f.color.setTo(cv::Scalar::all(0));
    slam.TrackRgbd(f.color, f.depth, f.timestamp);
  }
  slam.Shutdown();
  CoveredRun run;
  run.stats = slam.Stats();
  run.sources = slam.FrameSources();
  run.ate = eval::ComputeAte(*sequence.ground_truth(), slam.CameraTrajectory());
  return run;
}

int Posed(const RunStats& s) { return s.frames_tracked + s.frames_coasted; }

// "frame: source" for the frames around the gap, for a failure's message.
std::string SourcesAroundTheGap(const std::vector<FramePoseSource>& sources) {
  std::string out;
  const int last = std::min<int>(kCoveredTo + 40, static_cast<int>(sources.size()));
  for (int i = kCoveredFrom - 5; i < last; ++i) out += fmt::format("{}:{} ", i, ToString(sources[i].source));
  return out;
}

TEST(NewMapTest, ANewMapAfterTheGapIsMergedIntoTheOldOne) {
  DLSLAM_REQUIRE_SHARED_DATA(folder, "7scenes-redkitchen-500");
  const CoveredRun with = RunCovered(folder, TrackerOptions().new_map_after_lost_frames);
  const CoveredRun without = RunCovered(folder, 0);

  // Without new maps: lost after the gap until the camera is back near a keyframe.
  EXPECT_EQ(without.stats.maps_started, 0);
  int lost_after_gap = 0;
  for (int i = kCoveredTo; i < kFrames; ++i) lost_after_gap += without.sources[i].source == PoseSource::kNone;
  EXPECT_GE(lost_after_gap, 10) << SourcesAroundTheGap(without.sources);

  // With them: one map, started on the first frame after the gap, merged.
  EXPECT_EQ(with.stats.maps_started, 1);
  EXPECT_EQ(with.stats.maps_merged, 1);
  EXPECT_EQ(with.sources[kCoveredTo].source, PoseSource::kNewMap);
  int new_map = 0;
  for (int i = kCoveredTo; i < kFrames; ++i) {
    EXPECT_NE(with.sources[i].source, PoseSource::kNone) << "frame " << i;
    new_map += with.sources[i].source == PoseSource::kNewMap;
  }
  EXPECT_EQ(new_map, with.stats.frames_new_map);
  EXPECT_GT(new_map, 0);
  EXPECT_LT(new_map, 90);  // merged within 3 s
  // Merged, the new map's frames are in the old map's frame: the whole
  // trajectory stays as accurate as the one that waited for relocalization
  // (0.036 m here, 0.039 m with the merged frames, when measured).
  EXPECT_GT(Posed(with.stats), Posed(without.stats) + 10)
      << "with: " << SourcesAroundTheGap(with.sources) << "\nwithout: " << SourcesAroundTheGap(without.sources);
  EXPECT_EQ(static_cast<int>(with.ate.pairs), Posed(with.stats));
  EXPECT_LT(with.ate.error.rmse, 0.06);
  EXPECT_LT(with.ate.error.rmse, 1.5 * without.ate.error.rmse);
}

// As deployed, with local mapping and loop closing in their threads (the
// merge pauses local mapping from the tracking thread): every frame after
// the gap is posed, and the run ends cleanly (also under ThreadSanitizer).
// The mapping thread's timing decides which keyframe is the tracker's
// reference when the lens is covered; from some of them the old map finds
// the camera again on the first frame after the gap (3 runs in 16 when
// measured), otherwise a new map starts there and is merged.
TEST(NewMapTest, WithTheMappingThread) {
  DLSLAM_REQUIRE_SHARED_DATA(folder, "7scenes-redkitchen-500");
  const CoveredRun run = RunCovered(folder, TrackerOptions().new_map_after_lost_frames, /*sequential=*/false);
  const PoseSource first_after_gap = run.sources[kCoveredTo].source;
  if (run.stats.maps_started == 0) {
    EXPECT_TRUE(first_after_gap == PoseSource::kTracked || first_after_gap == PoseSource::kRelocalized)
        << SourcesAroundTheGap(run.sources);
  } else {
    EXPECT_EQ(first_after_gap, PoseSource::kNewMap) << SourcesAroundTheGap(run.sources);
    EXPECT_EQ(run.stats.maps_merged, run.stats.maps_started) << SourcesAroundTheGap(run.sources);
  }
  for (int i = kCoveredTo; i < kFrames; ++i) EXPECT_NE(run.sources[i].source, PoseSource::kNone) << "frame " << i;
  EXPECT_LT(run.ate.error.rmse, 0.1);
}

}  // namespace
}  // namespace dlslam
