#pragma once
// Even spatial distribution of corners by a quadtree (ORB-SLAM's scheme):
// nodes are split into four until there are as many nodes as corners wanted,
// then each node keeps its strongest corner.

#include <opencv2/core.hpp>

#include <vector>

#include "dlslam/features/fast_detector.h"

namespace dlslam::features {

// Keeps at most `target` corners of `corners` (all inside `area`), spread over
// `area`: the root nodes (about square, side by side) are split breadth first
// (nodes holding the most corners first within a round) until there are
// `target` non-empty nodes or every node holds one corner; each node keeps
// its highest score, and the weakest extra nodes of the last round are
// dropped. With `target` >= corners.size() every corner is kept. Reorders
// and shrinks `corners` in place.
void DistributeQuadtree(const cv::Rect& area, int target, std::vector<FastCorner>& corners);

}  // namespace dlslam::features
