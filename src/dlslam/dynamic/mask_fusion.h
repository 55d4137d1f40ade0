#pragma once
// Combines the semantic prior (segments of a-priori dynamic classes, e.g.
// people, and of movable ones, e.g. chairs) with the geometry result into the
// mask of pixels whose keypoints and map points the system drops.

#include <opencv2/core.hpp>

#include <string>

#include "dlslam/dynamic/geometry_detector.h"

namespace dlslam::dynamic {

enum class FusionPolicy {
  // semantic OR geometry: the paper's policy.
  kUnion,
  // Geometry regions are always dropped; a semantic segment (connected
  // component) is kept for SLAM when geometry shows it still: at least
  // min_static_evidence static points inside and at most
  // max_dynamic_evidence dynamic ones (e.g. people sitting). Without enough
  // evidence a segment is dropped, as in kUnion.
  kGeometryConfirms,
  kSemanticOnly,
  kGeometryOnly,
};
// "union", "geometry_confirms", "semantic", "geometry".
std::string ToString(FusionPolicy policy);
// Parses the names above; throws dlslam::Error listing them otherwise.
FusionPolicy ParseFusionPolicy(const std::string& name);

// What the segmentation says about a frame. Both CV_8UC1 (non-zero = the
// class) at the frame's size, or empty.
struct SemanticMasks {
  // A-priori dynamic classes (people): dropped as the policy says.
  cv::Mat dynamic{};
  // Movable classes (chairs, boxes): static structure until geometry shows
  // one moving; then the whole segment is dropped, not only the grown region
  // around its moving points (policies union and geometry_confirms).
  cv::Mat movable{};
};

struct FusionOptions {
  FusionPolicy policy = FusionPolicy::kUnion;
  // kGeometryConfirms: static points a semantic segment needs to be kept.
  int min_static_evidence = 5;
  // kGeometryConfirms: dynamic points a kept segment may contain (outliers).
  int max_dynamic_evidence = 0;
  // Drop a movable segment (connected component) whole when geometry finds
  // at least movable_dynamic_evidence moving or vanished points in it, and
  // they are at least movable_dynamic_share of its tested points (static +
  // moving + vanished). Points inside the a-priori dynamic mask are the
  // people's evidence, not the object's, and are not counted. Why the share:
  // on the real Bonn crowd a static chair beside the walkers collects a few
  // moving labels at its edges in most frames (parallax at a see-through
  // chair back, the walkers' outlines) and was dropped whole in 155 of 300
  // frames at 3 points; a pushed object's points disagree nearly all.
  bool drop_moving_movables = true;
  int movable_dynamic_evidence = 3;
  double movable_dynamic_share = 0.5;
  // The fused mask is dilated by this radius [px] (elliptic kernel): keypoint
  // patches near a silhouette see the mover too. 0 = no dilation.
  double dilation_px = 5.0;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

// `geometry`: a GeometryResult, or one with an empty dynamic_mask when the
// geometry check did not run. Returns CV_8UC1, 255 = dynamic, of the size of
// whichever input is present; an empty Mat when all are empty. Throws
// dlslam::Error when inputs are present with different sizes or a wrong type.
// `movable_segments_dropped` (optional) receives the number of movable
// segments dropped whole.
cv::Mat FuseDynamicMasks(const SemanticMasks& semantic, const GeometryResult& geometry,
                         const FusionOptions& options, int* movable_segments_dropped = nullptr);

}  // namespace dlslam::dynamic
