// Per-frame cost of the geometry check at 640x480: GeometryDetector::Detect()
// with 5 reference keyframes of ~1000 ORB keypoints each, on a rendered
// walking_xyz frame with ground-truth poses (frames rendered once, outside
// the timing). Paper (Table 4): 136-190 ms per frame for its geometry thread.

#include <benchmark/benchmark.h>

#include "dlslam/dynamic/free_space.h"
#include "dlslam/dynamic/geometry_detector.h"
#include "dlslam/dynamic/mask_fusion.h"
#include "dlslam/dynamic/mask_warp.h"
#include "dlslam/dynamic/region_growing.h"
#include "dlslam/dynamic/tools/keyframe_eval.h"

namespace {

using namespace dlslam;
using namespace dlslam::dynamic;

struct Fixture {
  cv::Mat depth;
  SE3d cam_from_world;
  CameraIntrinsics camera;
  std::vector<ReferenceView> references;
  std::vector<std::pair<cv::Mat, SE3d>> views;  // frames 45, 50, 55: depth, cam_from_world
  cv::Mat objects;                              // the frame's rendered objects (people, chairs): 255
};

const Fixture& GetFixture() {
  static const Fixture fixture = [] {
    synth::SynthOptions options;
    options.preset = synth::Preset::kWalkingXyz;
    options.frames = 61;
    const synth::SynthSequence sequence(options);
    evaluation::SynthFrameCache cache(sequence);
    Fixture f;
    f.camera = options.camera;
    const auto& current = cache.Get(60);
    f.depth = current.rendered.depth;
    f.cam_from_world = current.rendered.world_from_cam.Inverse();
    f.objects = current.rendered.mask != 0;
    for (int r = 1; r <= 5; ++r) {
      const auto& keyframe = cache.Get(60 - 6 * r);
      f.references.push_back(evaluation::MakeReferenceView(
          keyframe.rendered.depth, keyframe.keypoints, f.camera, keyframe.rendered.world_from_cam,
          static_cast<std::uint64_t>(r) << 20));
    }
    for (const int k : {45, 50, 55}) {
      const auto& view = cache.Get(k);
      f.views.emplace_back(view.rendered.depth, view.rendered.world_from_cam.Inverse());
    }
    return f;
  }();
  return fixture;
}

void BM_Detect(benchmark::State& state) {
  const Fixture& f = GetFixture();
  GeometryOptions options;
  options.search = state.range(0) == 0 ? SearchKind::kExhaustive : SearchKind::kAntColony;
  GeometryDetector detector(options);
  GeometryResult result;
  for (auto _ : state) {
    result = detector.Detect(f.depth, f.camera, f.cam_from_world, f.references);
    benchmark::DoNotOptimize(result.dynamic_mask.data);
  }
  state.SetLabel(ToString(options.search));
  state.counters["projected"] = result.points_projected;
  state.counters["tested"] = result.points_tested;
  state.counters["dynamic"] = result.points_dynamic;
}
BENCHMARK(BM_Detect)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The stages alone (exhaustive): projection, classification, region growing.
void BM_Project(benchmark::State& state) {
  const Fixture& f = GetFixture();
  std::vector<ProjectedPoint> points;
  for (auto _ : state) {
    ProjectReferencePoints(f.references, f.cam_from_world, f.camera, points);
    benchmark::DoNotOptimize(points.data());
  }
}
BENCHMARK(BM_Project)->Unit(benchmark::kMicrosecond);

void BM_ClassifyAll(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const auto points = ProjectReferencePoints(f.references, f.cam_from_world, f.camera);
  const MultiViewOptions options;
  for (auto _ : state) {
    int dynamic = 0;
    for (const ProjectedPoint& p : points) dynamic += ClassifyPoint(p, f.depth, options) == PointLabel::kDynamic;
    benchmark::DoNotOptimize(dynamic);
  }
}
BENCHMARK(BM_ClassifyAll)->Unit(benchmark::kMicrosecond);

void BM_Search(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const auto points = ProjectReferencePoints(f.references, f.cam_from_world, f.camera);
  const MultiViewOptions options;
  auto search = state.range(0) == 0 ? MakeExhaustiveSearch() : MakeAntColonySearch({});
  for (auto _ : state) {
    SearchResult r = search->Search(points, f.depth.size(), [&](std::size_t i) {
      return ClassifyPoint(points[i], f.depth, options);
    });
    benchmark::DoNotOptimize(r.labels.data());
  }
  state.SetLabel(state.range(0) == 0 ? "exhaustive" : "ant");
}
BENCHMARK(BM_Search)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// A person covering a third of a 640x480 frame carried 10 cm of camera motion
// (what the tracker would do with the newest mask instead of waiting), grown
// by 16 px (two frames of age); arg: the cell size [px] (1 = every pixel).
void BM_MaskWarp(benchmark::State& state) {
  const CameraIntrinsics camera = CameraPreset("bonn");
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  mask(cv::Rect(200, 0, 213, 480)).setTo(255);
  const cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(1.5f));
  const MaskWarper warper(camera, MaskWarpOptions{.cell_px = static_cast<int>(state.range(0))});
  const SE3d motion(Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY())), Eigen::Vector3d(0.1, 0, 0));
  for (auto _ : state) benchmark::DoNotOptimize(warper.Warp(mask, depth, motion, 16));
}
BENCHMARK(BM_MaskWarp)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

// The dense free-space check (free_space.h): keeping a view (every 5th
// tracked frame), and checking a frame against the 3 kept views.
void BM_FreeSpaceOffer(benchmark::State& state) {
  const Fixture& f = GetFixture();
  FreeSpaceCheck check(f.camera, FreeSpaceOptions{.view_every_frames = 1});
  for (auto _ : state) check.Offer(f.views[0].first, f.views[0].second);
}
BENCHMARK(BM_FreeSpaceOffer)->Unit(benchmark::kMillisecond);

// Arg 1: with the Bonn Xtion's lens distortion (CameraPreset("bonn")) on the
// rendered camera, as on the real Bonn frames: a distortion per projection.
void BM_FreeSpaceViolations(benchmark::State& state) {
  const Fixture& f = GetFixture();
  CameraIntrinsics camera = f.camera;
  if (state.range(0) == 1) {
    const CameraIntrinsics bonn = CameraPreset("bonn");
    camera.k1 = bonn.k1;
    camera.k2 = bonn.k2;
    camera.p1 = bonn.p1;
    camera.p2 = bonn.p2;
    camera.k3 = bonn.k3;
  }
  FreeSpaceCheck check(camera, FreeSpaceOptions{.view_every_frames = 1});
  for (const auto& [depth, pose] : f.views) check.Offer(depth, pose);
  cv::Mat moved;
  for (auto _ : state) {
    moved = check.Violations(f.depth, f.cam_from_world);
    benchmark::DoNotOptimize(moved.data);
  }
  state.counters["moved_in_share"] = cv::countNonZero(moved) / static_cast<double>(moved.total());
}
BENCHMARK(BM_FreeSpaceViolations)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Detect with the check's violations as extra seeds (ant colony search).
void BM_DetectWithFreeSpace(benchmark::State& state) {
  const Fixture& f = GetFixture();
  FreeSpaceCheck check(f.camera, FreeSpaceOptions{.view_every_frames = 1});
  for (const auto& [depth, pose] : f.views) check.Offer(depth, pose);
  const cv::Mat moved = check.Violations(f.depth, f.cam_from_world);
  GeometryDetector detector(GeometryOptions{});
  GeometryResult result;
  for (auto _ : state) {
    result = detector.Detect(f.depth, f.camera, f.cam_from_world, f.references, moved);
    benchmark::DoNotOptimize(result.dynamic_mask.data);
  }
}
BENCHMARK(BM_DetectWithFreeSpace)->Unit(benchmark::kMillisecond);

// Region growing alone over the frame's depth, seeded as the multi-view test
// leaves it: dynamic points on the people and chairs, static points on the
// rest (a point every 16 px).
void BM_GrowDynamicRegions(benchmark::State& state) {
  const Fixture& f = GetFixture();
  std::vector<cv::Point2f> dynamic_seeds, static_seeds;
  for (int v = 8; v < f.depth.rows; v += 16) {
    for (int u = 8; u < f.depth.cols; u += 16) {
      (f.objects.at<std::uint8_t>(v, u) != 0 ? dynamic_seeds : static_seeds).emplace_back(u, v);
    }
  }
  const RegionGrowingOptions options;
  RegionGrowingBuffers buffers;  // as the geometry detector keeps them
  cv::Mat grown;
  for (auto _ : state) {
    grown = GrowDynamicRegions(f.depth, f.camera, dynamic_seeds, static_seeds, options, &buffers);
    benchmark::DoNotOptimize(grown.data);
  }
  state.counters["dynamic_seeds"] = static_cast<double>(dynamic_seeds.size());
  state.counters["static_seeds"] = static_cast<double>(static_seeds.size());
  state.counters["grown_share"] = cv::countNonZero(grown) / static_cast<double>(grown.total());
}
BENCHMARK(BM_GrowDynamicRegions)->Unit(benchmark::kMicrosecond);

// The dynamic stage's two fusions of a frame (mode full, policy union,
// dilation 5 px): the network's mask alone (DynamicStage::TakePrior), then
// with the geometry's regions (DynamicStage::Process).
void BM_FuseDynamicMasks(benchmark::State& state) {
  const Fixture& f = GetFixture();
  GeometryDetector detector(GeometryOptions{});
  const GeometryResult geometry = detector.Detect(f.depth, f.camera, f.cam_from_world, f.references);
  const FusionOptions options;
  for (auto _ : state) {
    benchmark::DoNotOptimize(FuseDynamicMasks({f.objects, {}}, {}, options).data);
    benchmark::DoNotOptimize(FuseDynamicMasks({f.objects, {}}, geometry, options).data);
  }
  state.counters["prior_share"] = cv::countNonZero(f.objects) / static_cast<double>(f.objects.total());
  state.counters["geometry_share"] =
      cv::countNonZero(geometry.dynamic_mask) / static_cast<double>(geometry.dynamic_mask.total());
}
BENCHMARK(BM_FuseDynamicMasks)->Unit(benchmark::kMillisecond);

}  // namespace
