#pragma once
// How SlamSystem handles moving objects (paper Sec. III): the mode picks
// which detectors remove keypoints before tracking, the rest configures them.
//   orb       the ORB-SLAM3-style baseline: nothing is removed
//   semantic  keypoints on the caller's semantic a-priori mask are removed
//   geometry  multi-view geometry finds moving regions (no network)
//   full      semantic prior and geometry, combined by the fusion policy

#include <string>

#include "dlslam/dynamic/geometry_detector.h"
#include "dlslam/dynamic/mask_completion.h"
#include "dlslam/dynamic/mask_fusion.h"

namespace dlslam {

enum class DynamicMode { kOrb, kSemantic, kGeometry, kFull };

// "orb", "semantic", "geometry", "full".
const char* ToString(DynamicMode mode);
// The inverse of ToString; throws dlslam::Error naming the choices.
DynamicMode ParseDynamicMode(const std::string& name);

// Whether the mode uses the semantic prior / the geometric detector.
bool UsesSemanticPrior(DynamicMode mode);
bool UsesGeometry(DynamicMode mode);

struct DynamicOptions {
  DynamicMode mode = DynamicMode::kOrb;
  // The multi-view check, its search (exhaustive or ant colony) and region
  // growing. geometry.multiview.max_reference_views is how many earlier
  // keyframes are projected into each frame (paper: 5).
  dynamic::GeometryOptions geometry;
  // How the semantic prior and the geometric mask combine in mode full, and
  // the dilation of the removal mask in every mode (modes semantic and
  // geometry use policies semantic and geometry with the same dilation).
  dynamic::FusionOptions fusion;
  // Modes semantic and full: the network's person mask completed with the
  // depth (the parts of a body it missed beside what it found) before
  // anything uses it.
  dynamic::MaskCompletionOptions completion;
  // Map points that geometry shows to have moved away (a reference keyframe
  // saw them, the current depth sees through where they were) are removed
  // from the map, so tracking never matches them again.
  bool cull_vanished_points = true;
  // When the people hold most of the texture, the first pose estimate
  // follows them and the check then calls the static scene moving. When
  // geometry marks at least inverted_check_min_share of the image, the check
  // is run again with a pose estimated from the keypoints inside the marked
  // region only, and the labelling that marks less of the image wins (the
  // static scene is the larger part of the view, counted in pixels, not in
  // keypoints). Not in frames with a semantic prior: the estimate already
  // left the prior's keypoints out.
  bool resolve_inverted_check = true;
  double inverted_check_min_share = 0.15;  // (0, 1]
  // Mode full: when geometry would take more than this share of the
  // keypoints the semantic prior leaves, the check is taken to have failed,
  // not the scene to move: its pose estimate stood on what the prior left
  // (in a crowd, a few keypoints, many on people's outlines), and a wrong
  // estimate makes the static rest look moving. The frame keeps the prior's
  // removal only. Real Bonn crowd: with 85 % of a frame's keypoints on
  // people, geometry took 134 of the remaining 152 and tracking coasted for
  // 14 frames. (0, 1]; 1 = always trust geometry. (Overruling only frames
  // left with < 10 % static keypoints did worse on the semi-real seeds.)
  double max_geometry_share_of_prior_static = 0.5;
  // geometry.multiview.parallax_occlusion_check in mode geometry too? Mode
  // full uses it as set: there the network covers the people, and geometry's
  // false alarms on still chairs and floor only cost static structure
  // (semi-real, 12 sequences: sum of ATE 0.662 -> 0.581 m). Alone, geometry
  // must catch the people as well, and the few movers the check lets go cost
  // more than the still structure it gives back (semi-real: recall 0.917 ->
  // 0.912, within 1.3x of the empty kitchen 7 -> 4 of 12; docs/real-data.md).
  bool geometry_mode_parallax_check = false;

  // The geometry detector's options in this mode.
  dynamic::GeometryOptions GeometryInMode() const;

  void Check() const;
};

}  // namespace dlslam
