#include "dlslam/dynamic/geometry_detector.h"

#include "dlslam/dynamic/ant_colony_search.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {

std::string ToString(SearchKind kind) {
  return kind == SearchKind::kExhaustive ? "exhaustive" : "ant";
}

SearchKind ParseSearchKind(const std::string& name) {
  if (name == "exhaustive") return SearchKind::kExhaustive;
  if (name == "ant" || name == "ant_colony") return SearchKind::kAntColony;
  throw Error(fmt::format("unknown search strategy '{}' (valid: exhaustive, ant)", name));
}

void GeometryOptions::Check() const {
  multiview.Check();
  ant.Check();
  region.Check();
  free_space.Check();
}

GeometryDetector::GeometryDetector(const GeometryOptions& options) : options_(options) {
  options_.Check();
  if (options_.search == SearchKind::kAntColony) {
    search_ = MakeAntColonySearch(options_.ant);
  } else {
    search_ = MakeExhaustiveSearch();
  }
}

GeometryDetector::~GeometryDetector() = default;
GeometryDetector::GeometryDetector(GeometryDetector&&) noexcept = default;
GeometryDetector& GeometryDetector::operator=(GeometryDetector&&) noexcept = default;

GeometryResult GeometryDetector::Detect(const cv::Mat& depth, const CameraIntrinsics& intrinsics,
                                        const SE3d& cam_from_world,
                                        const std::vector<ReferenceView>& references,
                                        const cv::Mat& moved_in) {
  DLSLAM_CHECK(depth.type() == CV_32FC1,
               "GeometryDetector: depth must be CV_32FC1 metres, got OpenCV type {}", depth.type());
  DLSLAM_CHECK(depth.cols == intrinsics.width && depth.rows == intrinsics.height,
               "GeometryDetector: depth is {}x{}, the camera {}x{}", depth.cols, depth.rows,
               intrinsics.width, intrinsics.height);
  GeometryResult result;
  ProjectReferencePoints(references, cam_from_world, intrinsics, result.points,
                         static_cast<std::size_t>(options_.multiview.max_reference_views));
  const std::size_t n = result.points.size();
  depth_pixels_.resize(n);
  const MultiViewOptions& multiview = options_.multiview;
  SearchResult search = search_->Search(
      result.points, depth.size(), [&](std::size_t i) {
        const ProjectedPoint& p = result.points[i];
        const PointLabel label = ClassifyPoint(p, depth, multiview, &depth_pixels_[i]);
        if (label != PointLabel::kDynamic) return label;
        const ReferenceView& view = references[static_cast<std::size_t>(p.view)];
        const double measured = depth.at<float>(depth_pixels_[i]);
        return OcclusionProvesMotion(view.points[static_cast<std::size_t>(p.point)].position_world,
                                     view.cam_from_world, cam_from_world, measured, depth, intrinsics, multiview)
                   ? label
                   : PointLabel::kOccluded;
      });
  result.labels = std::move(search.labels);
  result.points_projected = static_cast<int>(n);
  result.points_tested = search.tested;

  std::vector<cv::Point2f> seeds, barriers;
  for (std::size_t i = 0; i < n; ++i) {
    const PointLabel label = result.labels[i];
    if (label == PointLabel::kStatic) {
      barriers.emplace_back(depth_pixels_[i]);
    } else if (label == PointLabel::kDynamic) {
      ++result.points_dynamic;
      seeds.emplace_back(depth_pixels_[i]);
    } else if (label == PointLabel::kVanished) {
      ++result.points_vanished;
      if (options_.grow_from_vanished) {
        seeds.emplace_back(depth_pixels_[i]);
      } else if (options_.vanished_as_barriers) {
        barriers.emplace_back(depth_pixels_[i]);
      }
      const ProjectedPoint& p = result.points[i];
      const std::uint64_t id = references[static_cast<std::size_t>(p.view)]
                                   .points[static_cast<std::size_t>(p.point)]
                                   .id;
      if (id != std::numeric_limits<std::uint64_t>::max()) result.vanished_ids.push_back(id);
    }
  }
  if (!moved_in.empty()) {
    DLSLAM_CHECK(moved_in.type() == CV_8UC1 && moved_in.size() == depth.size(),
                 "GeometryDetector: moved_in must be CV_8UC1 {}x{}, got type {} {}x{}", depth.cols, depth.rows,
                 moved_in.type(), moved_in.cols, moved_in.rows);
    // One seed per cell of the dense check is plenty: the fill joins them.
    const int step = options_.free_space.cell_px;
    for (int v = step / 2; v < moved_in.rows; v += step) {
      const auto* row = moved_in.ptr<std::uint8_t>(v);
      for (int u = step / 2; u < moved_in.cols; u += step) {
        if (row[u] != 0) seeds.emplace_back(static_cast<float>(u), static_cast<float>(v));
      }
    }
  }
  result.dynamic_mask = GrowDynamicRegions(depth, intrinsics, seeds, barriers, options_.region, &region_buffers_);
  if (!moved_in.empty()) result.dynamic_mask |= moved_in;
  return result;
}

}  // namespace dlslam::dynamic
