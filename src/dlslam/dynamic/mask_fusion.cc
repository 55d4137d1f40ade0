#include "dlslam/dynamic/mask_fusion.h"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

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
  DLSLAM_CHECK(dilation_px >= 0 && dilation_px <= 100,
               "FusionOptions::dilation_px {} outside [0, 100]", dilation_px);
}

namespace {

// Semantic segments the geometry shows still: a 0/255 mask of the prior's
// connected components that have enough static and few enough dynamic points.
cv::Mat StillSegments(const cv::Mat& prior, const GeometryResult& geometry,
                      const FusionOptions& options) {
  cv::Mat components;
  const int count = cv::connectedComponents(prior, components, 8, CV_32S);
  std::vector<int> static_points(static_cast<std::size_t>(count), 0);
  std::vector<int> dynamic_points(static_cast<std::size_t>(count), 0);
  for (std::size_t i = 0; i < geometry.points.size() && i < geometry.labels.size(); ++i) {
    const int u = static_cast<int>(std::lround(geometry.points[i].pixel.x()));
    const int v = static_cast<int>(std::lround(geometry.points[i].pixel.y()));
    if (u < 0 || v < 0 || u >= components.cols || v >= components.rows) continue;
    const auto segment = static_cast<std::size_t>(components.at<int>(v, u));
    if (segment == 0) continue;  // background
    const PointLabel label = geometry.labels[i];
    if (label == PointLabel::kStatic) ++static_points[segment];
    if (label == PointLabel::kDynamic || label == PointLabel::kVanished) ++dynamic_points[segment];
  }
  std::vector<std::uint8_t> still(static_cast<std::size_t>(count), 0);
  for (std::size_t s = 1; s < still.size(); ++s) {
    still[s] = static_points[s] >= options.min_static_evidence &&
               dynamic_points[s] <= options.max_dynamic_evidence;
  }
  cv::Mat out = cv::Mat::zeros(prior.size(), CV_8UC1);
  for (int v = 0; v < prior.rows; ++v) {
    const int* row = components.ptr<int>(v);
    std::uint8_t* out_row = out.ptr<std::uint8_t>(v);
    for (int u = 0; u < prior.cols; ++u) {
      if (still[static_cast<std::size_t>(row[u])]) out_row[u] = 255;
    }
  }
  return out;
}

}  // namespace

cv::Mat FuseDynamicMasks(const cv::Mat& semantic_prior, const GeometryResult& geometry,
                         const FusionOptions& options) {
  options.Check();
  const cv::Mat& geometry_mask = geometry.dynamic_mask;
  if (!semantic_prior.empty()) {
    DLSLAM_CHECK(semantic_prior.type() == CV_8UC1,
                 "FuseDynamicMasks: semantic prior must be CV_8UC1, got OpenCV type {}",
                 semantic_prior.type());
  }
  if (!geometry_mask.empty()) {
    DLSLAM_CHECK(geometry_mask.type() == CV_8UC1,
                 "FuseDynamicMasks: geometry mask must be CV_8UC1, got OpenCV type {}",
                 geometry_mask.type());
  }
  if (!semantic_prior.empty() && !geometry_mask.empty()) {
    DLSLAM_CHECK(semantic_prior.size() == geometry_mask.size(),
                 "FuseDynamicMasks: semantic prior {}x{} and geometry mask {}x{} differ",
                 semantic_prior.cols, semantic_prior.rows, geometry_mask.cols, geometry_mask.rows);
  }
  if (semantic_prior.empty() && geometry_mask.empty()) return {};
  const cv::Size size = semantic_prior.empty() ? geometry_mask.size() : semantic_prior.size();
  const cv::Mat zeros = cv::Mat::zeros(size, CV_8UC1);
  cv::Mat prior = zeros.clone();
  if (!semantic_prior.empty()) prior.setTo(255, semantic_prior != 0);
  cv::Mat moving = zeros.clone();
  if (!geometry_mask.empty()) moving.setTo(255, geometry_mask != 0);

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
    if (r > 0) {
      const cv::Mat kernel =
          cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1));
      cv::dilate(fused, fused, kernel);
    }
  }
  return fused;
}

}  // namespace dlslam::dynamic
