#include "dlslam/dynamic/mask_fusion.h"

#include <cmath>
#include <vector>

#include "dlslam/image/connected_components.h"
#include "dlslam/image/disc_dilation.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {

std::string ToString(FusionPolicy policy) {
  switch (policy) {
    case FusionPolicy::kUnion: return "union";
    case FusionPolicy::kGeometryConfirms: return "geometry_confirms";
    case FusionPolicy::kSemanticOnly: return "semantic";
    case FusionPolicy::kGeometryOnly: return "geometry";
  }
  return "?";
}

FusionPolicy ParseFusionPolicy(const std::string& name) {
  for (const FusionPolicy p : {FusionPolicy::kUnion, FusionPolicy::kGeometryConfirms,
                               FusionPolicy::kSemanticOnly, FusionPolicy::kGeometryOnly}) {
    if (name == ToString(p)) return p;
  }
  throw Error(fmt::format(
      "unknown fusion policy '{}' (valid: union, geometry_confirms, semantic, geometry)", name));
}

void FusionOptions::Check() const {
  DLSLAM_CHECK_GE(min_static_evidence, 0, "FusionOptions::min_static_evidence");
  DLSLAM_CHECK_GE(max_dynamic_evidence, 0, "FusionOptions::max_dynamic_evidence");
  DLSLAM_CHECK_GE(movable_dynamic_evidence, 1, "FusionOptions::movable_dynamic_evidence");
  DLSLAM_CHECK(movable_dynamic_share >= 0.0 && movable_dynamic_share <= 1.0,
               "FusionOptions::movable_dynamic_share {} outside [0, 1]", movable_dynamic_share);
  DLSLAM_CHECK(dilation_px >= 0 && dilation_px <= 100,
               "FusionOptions::dilation_px {} outside [0, 100]", dilation_px);
}

namespace {

// The connected components of a 0/non-zero mask and the geometry's evidence
// in each: static points, and moving or vanished ones. Label 0 = outside.
struct Segments {
  cv::Mat labels;  // CV_32S
  std::vector<int> static_points, dynamic_points;
};

// Points on a non-zero pixel of `ignore` (optional) are not counted.
Segments CountEvidence(const cv::Mat& mask, const GeometryResult& geometry, const cv::Mat& ignore = {}) {
  Segments s;
  const int count = image::LabelComponents(mask, s.labels);
  s.static_points.assign(static_cast<std::size_t>(count), 0);
  s.dynamic_points.assign(static_cast<std::size_t>(count), 0);
  for (std::size_t i = 0; i < geometry.points.size() && i < geometry.labels.size(); ++i) {
    const int u = static_cast<int>(std::lround(geometry.points[i].pixel.x()));
    const int v = static_cast<int>(std::lround(geometry.points[i].pixel.y()));
    if (u < 0 || v < 0 || u >= s.labels.cols || v >= s.labels.rows) continue;
    if (!ignore.empty() && ignore.at<std::uint8_t>(v, u) != 0) continue;
    const auto segment = static_cast<std::size_t>(s.labels.at<int>(v, u));
    if (segment == 0) continue;  // outside every segment
    const PointLabel label = geometry.labels[i];
    if (label == PointLabel::kStatic) ++s.static_points[segment];
    if (label == PointLabel::kDynamic || label == PointLabel::kVanished) ++s.dynamic_points[segment];
  }
  return s;
}

// 255 on the segments whose flag is set.
cv::Mat Paint(const cv::Mat& labels, const std::vector<std::uint8_t>& selected) {
  cv::Mat out = cv::Mat::zeros(labels.size(), CV_8UC1);
  for (int v = 0; v < labels.rows; ++v) {
    const int* row = labels.ptr<int>(v);
    std::uint8_t* out_row = out.ptr<std::uint8_t>(v);
    for (int u = 0; u < labels.cols; ++u) {
      if (selected[static_cast<std::size_t>(row[u])]) out_row[u] = 255;
    }
  }
  return out;
}

// Semantic segments the geometry shows still: enough static and few enough
// dynamic points.
cv::Mat StillSegments(const cv::Mat& prior, const GeometryResult& geometry, const FusionOptions& options) {
  const Segments s = CountEvidence(prior, geometry);
  std::vector<std::uint8_t> still(s.static_points.size(), 0);
  for (std::size_t i = 1; i < still.size(); ++i) {
    still[i] = s.static_points[i] >= options.min_static_evidence &&
               s.dynamic_points[i] <= options.max_dynamic_evidence;
  }
  return Paint(s.labels, still);
}

// Moving or vanished points of the geometry on a 0/non-zero mask.
int DynamicPointsOn(const cv::Mat& mask, const GeometryResult& geometry) {
  int count = 0;
  for (std::size_t i = 0; i < geometry.points.size() && i < geometry.labels.size(); ++i) {
    const PointLabel label = geometry.labels[i];
    if (label != PointLabel::kDynamic && label != PointLabel::kVanished) continue;
    const int u = static_cast<int>(std::lround(geometry.points[i].pixel.x()));
    const int v = static_cast<int>(std::lround(geometry.points[i].pixel.y()));
    if (u >= 0 && v >= 0 && u < mask.cols && v < mask.rows && mask.at<std::uint8_t>(v, u) != 0) ++count;
  }
  return count;
}

// Movable segments the geometry shows moving (empty when none); their count
// in `dropped`. Evidence on `people` (the a-priori dynamic mask) is theirs.
cv::Mat MovingSegments(const cv::Mat& movable, const cv::Mat& people, const GeometryResult& geometry,
                       const FusionOptions& options, int* dropped) {
  // No segment can hold more evidence than the whole mask: then the
  // segments need not be found (most frames; ~0.6 ms at 640x480).
  if (DynamicPointsOn(movable, geometry) < options.movable_dynamic_evidence) return {};
  const Segments s = CountEvidence(movable, geometry, people);
  std::vector<std::uint8_t> moving(s.dynamic_points.size(), 0);
  for (std::size_t i = 1; i < moving.size(); ++i) {
    const int dynamic = s.dynamic_points[i];
    moving[i] = dynamic >= options.movable_dynamic_evidence &&
                dynamic >= options.movable_dynamic_share * (dynamic + s.static_points[i]);
    *dropped += moving[i];
  }
  return Paint(s.labels, moving);
}

// Checks a mask's type and its size against `size` (taken from it when empty).
void CheckMask(const cv::Mat& mask, const char* what, cv::Size* size) {
  if (mask.empty()) return;
  DLSLAM_CHECK(mask.type() == CV_8UC1, "FuseDynamicMasks: {} must be CV_8UC1, got OpenCV type {}", what,
               mask.type());
  if (size->empty()) *size = mask.size();
  DLSLAM_CHECK(mask.size() == *size, "FuseDynamicMasks: {} is {}x{}, the other inputs {}x{}", what, mask.cols,
               mask.rows, size->width, size->height);
}

}  // namespace

cv::Mat FuseDynamicMasks(const SemanticMasks& semantic, const GeometryResult& geometry,
                         const FusionOptions& options, int* movable_segments_dropped) {
  options.Check();
  if (movable_segments_dropped != nullptr) *movable_segments_dropped = 0;
  const cv::Mat& geometry_mask = geometry.dynamic_mask;
  cv::Size size;
  CheckMask(semantic.dynamic, "the semantic prior", &size);
  CheckMask(semantic.movable, "the movable-class mask", &size);
  CheckMask(geometry_mask, "the geometry mask", &size);
  if (size.empty()) return {};
  const cv::Mat zeros = cv::Mat::zeros(size, CV_8UC1);
  cv::Mat prior = zeros.clone();
  if (!semantic.dynamic.empty()) prior.setTo(255, semantic.dynamic != 0);
  cv::Mat moving = zeros.clone();
  if (!geometry_mask.empty()) moving.setTo(255, geometry_mask != 0);
  const bool uses_movables = options.drop_moving_movables && !semantic.movable.empty() && !geometry_mask.empty() &&
                             (options.policy == FusionPolicy::kUnion ||
                              options.policy == FusionPolicy::kGeometryConfirms);
  if (uses_movables) {
    int dropped = 0;
    const cv::Mat moving_movables = MovingSegments(semantic.movable, semantic.dynamic, geometry, options, &dropped);
    if (!moving_movables.empty()) moving |= moving_movables;
    if (movable_segments_dropped != nullptr) *movable_segments_dropped = dropped;
  }

  cv::Mat fused;
  switch (options.policy) {
    case FusionPolicy::kUnion: fused = prior | moving; break;
    case FusionPolicy::kSemanticOnly: fused = prior; break;
    case FusionPolicy::kGeometryOnly: fused = moving; break;
    case FusionPolicy::kGeometryConfirms: {
      cv::Mat kept_prior = prior.clone();
      if (!geometry_mask.empty()) kept_prior.setTo(0, StillSegments(prior, geometry, options));
      fused = kept_prior | moving;
      break;
    }
  }
  if (options.dilation_px > 0) {
    const int r = static_cast<int>(std::lround(options.dilation_px));
    if (r > 0) image::DilateDisc(fused, r, fused);
  }
  return fused;
}

}  // namespace dlslam::dynamic
