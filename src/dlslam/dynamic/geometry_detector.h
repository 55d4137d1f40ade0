#pragma once
// The geometry thread's per-frame work: project the reference views into the
// current frame, test the projected points with a search strategy
// (exhaustive or ant colony), grow the dynamic points into regions of the
// depth image. Keeps its buffers and the ant colony's pheromone across
// frames: one detector per sequence, not thread-safe.

#include <opencv2/core.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/dynamic/free_space.h"
#include "dlslam/dynamic/multiview.h"
#include "dlslam/dynamic/point_search.h"
#include "dlslam/dynamic/region_growing.h"
#include "dlslam/geometry/se3.h"

namespace dlslam::dynamic {

enum class SearchKind { kExhaustive, kAntColony };
// "exhaustive", "ant".
std::string ToString(SearchKind kind);
// Parses "exhaustive" or "ant" ("ant_colony" too); throws dlslam::Error
// listing the valid names otherwise.
SearchKind ParseSearchKind(const std::string& name);

struct GeometryOptions {
  MultiViewOptions multiview;
  SearchKind search = SearchKind::kAntColony;
  AntColonyOptions ant;  // used when search == kAntColony
  RegionGrowingOptions region;
  // Grow regions from vanished points too? No: a vanished point's current
  // pixel shows what was behind it, not the mover. Kept as an option for
  // experiments.
  bool grow_from_vanished = false;
  // A vanished point's current pixel shows the background that was behind
  // it: use it as static evidence (a barrier for region growing) like the
  // static points. Ignored when grow_from_vanished.
  bool vanished_as_barriers = true;
  // The dense free-space check against recent frames (free_space.h); its
  // violations seed the region growing and are removed themselves.
  FreeSpaceOptions free_space;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

struct GeometryResult {
  cv::Mat dynamic_mask;                // CV_8UC1, 255 = moving region; empty if not run
  std::vector<ProjectedPoint> points;  // every projected reference point
  std::vector<PointLabel> labels;      // one per point (kUntested: skipped by the search)
  int points_projected = 0;
  int points_tested = 0;
  int points_dynamic = 0;
  int points_vanished = 0;
  // ids (ReferencePoint::id) of the vanished points, without the "no id"
  // value; the system may cull these map points.
  std::vector<std::uint64_t> vanished_ids;
};

class GeometryDetector {
 public:
  explicit GeometryDetector(const GeometryOptions& options);  // checks options
  ~GeometryDetector();
  GeometryDetector(GeometryDetector&&) noexcept;
  GeometryDetector& operator=(GeometryDetector&&) noexcept;

  // `depth`: CV_32FC1 metres of the current frame, intrinsics.width x height.
  // `references`: earlier keyframes, most relevant first (only the first
  // multiview.max_reference_views are used). `moved_in`: CV_8UC1 of the
  // depth's size (or empty), non-zero where something is known to have moved
  // in (FreeSpaceCheck::Violations): dynamic seeds every few pixels, and
  // part of the result. Throws dlslam::Error on a depth image of the wrong
  // type or size.
  GeometryResult Detect(const cv::Mat& depth, const CameraIntrinsics& intrinsics,
                        const SE3d& cam_from_world, const std::vector<ReferenceView>& references,
                        const cv::Mat& moved_in = {});

  const GeometryOptions& options() const { return options_; }

 private:
  GeometryOptions options_;
  std::unique_ptr<PointSearch> search_;
  std::vector<cv::Point> depth_pixels_;  // per point: the pixel that decided (buffer)
  RegionGrowingBuffers region_buffers_;
};

}  // namespace dlslam::dynamic
