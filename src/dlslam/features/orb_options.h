#pragma once
// Options of the ORB extractor (ORB-SLAM3's design: FAST on a grid with a
// threshold fallback, quadtree distribution per pyramid level, steered BRIEF).

#include <vector>

namespace dlslam::features {

// Side of the square patch that orientation and descriptors read [px]; the
// learned test pattern is made for this size, so it is a constant.
inline constexpr int kPatchSize = 31;
inline constexpr int kPatchRadius = kPatchSize / 2;  // 15 px
// Bytes of one descriptor (256 binary tests).
inline constexpr int kDescriptorBytes = 32;

struct OrbOptions {
  // Keypoints wanted over all pyramid levels (fewer when the image has too
  // little texture). ORB-SLAM's value for 640x480 RGB-D.
  int n_features = 1000;
  // Pyramid levels (level 0 = the input image).
  int n_levels = 8;
  // Size ratio between consecutive pyramid levels (> 1).
  double scale_factor = 1.2;
  // FAST intensity threshold [grey levels, 0..255] tried first in every grid cell.
  int fast_threshold_initial = 20;
  // FAST threshold [grey levels] used in cells where the initial one found
  // nothing; must not exceed fast_threshold_initial.
  int fast_threshold_min = 7;
  // Side of the square grid cells FAST thresholds are chosen for [px, at
  // every level].
  int cell_size = 30;
  // No keypoint closer than this to a level's edge [px at that level]; the
  // orientation patch and the rotated tests (radius <= 15) must fit inside.
  int edge_border = 19;
  // With an exclusion mask (people), a corner is left out when an excluded
  // pixel lies within this many pixels of it at its level [px at the level;
  // 0 = only the corner's own pixel]. FAST compares the circle of radius 3
  // around a corner: a corner that close to a person's outline may be made by
  // the outline and move with the person (a T-junction of a boot and the
  // floor behind it). 3 measured (docs/real-data.md): full mode a little
  // better on the real frames (Bonn 0.0152 vs 0.0157 m, 7-Scenes 0.0353 vs
  // 0.0381 m), a wash over 12 semi-real sequences, geometry alone on Bonn
  // 0.23 vs 0.042 m --sequential (threaded both 0.11-0.30 m): not the default.
  int exclusion_radius = 0;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

// Scale of each level relative to level 0: scale_factor^level.
std::vector<double> LevelScales(const OrbOptions& options);

// Keypoints wanted per level, summing to n_features. A geometric series with
// ratio 1/scale_factor, as ORB-SLAM distributes them (proportional to the
// level's side length, i.e. to the square root of its area).
std::vector<int> LevelFeatureTargets(const OrbOptions& options);

}  // namespace dlslam::features
