#include "dlslam/features/quadtree.h"

#include <algorithm>
#include <cmath>

namespace dlslam::features {
namespace {

struct Node {
  double x0, y0, x1, y1;  // box [x0, x1) x [y0, y1) in pixels
  int begin, end;         // corners[begin, end) lie in the box
  int count() const { return end - begin; }
  // Corners lie on integer pixels, so a box of at most 1 x 1 px holds one
  // pixel: splitting it further could never separate (duplicate) corners.
  bool splittable() const { return count() > 1 && (x1 - x0 > 1.0 || y1 - y0 > 1.0); }
};

using CornerIt = std::vector<FastCorner>::iterator;

// Splits `node` at its centre and appends its non-empty children to `out`.
void Split(const Node& node, std::vector<FastCorner>& corners, std::vector<Node>& out) {
  const double xm = 0.5 * (node.x0 + node.x1), ym = 0.5 * (node.y0 + node.y1);
  const CornerIt first = corners.begin() + node.begin, last = corners.begin() + node.end;
  const CornerIt top_end = std::partition(first, last, [&](const FastCorner& c) { return c.y < ym; });
  const CornerIt top_left_end =
      std::partition(first, top_end, [&](const FastCorner& c) { return c.x < xm; });
  const CornerIt bottom_left_end =
      std::partition(top_end, last, [&](const FastCorner& c) { return c.x < xm; });
  const auto index = [&](CornerIt it) { return static_cast<int>(it - corners.begin()); };
  const Node children[4] = {
      {node.x0, node.y0, xm, ym, node.begin, index(top_left_end)},
      {xm, node.y0, node.x1, ym, index(top_left_end), index(top_end)},
      {node.x0, ym, xm, node.y1, index(top_end), index(bottom_left_end)},
      {xm, ym, node.x1, node.y1, index(bottom_left_end), node.end}};
  for (const Node& child : children) {
    if (child.count() > 0) out.push_back(child);
  }
}

}  // namespace

void DistributeQuadtree(const cv::Rect& area, int target, std::vector<FastCorner>& corners) {
  if (target <= 0) {
    corners.clear();
    return;
  }
  if (corners.size() <= static_cast<size_t>(target)) return;

  // Roots: about square boxes side by side (one for 4:3 images).
  const int n_roots = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(area.width) / area.height)));
  const double root_width = static_cast<double>(area.width) / n_roots;
  std::vector<Node> nodes;
  int begin = 0;
  for (int r = 0; r < n_roots; ++r) {
    const double x0 = area.x + r * root_width;
    const double x1 = r + 1 == n_roots ? area.x + area.width + 1.0 : x0 + root_width;
    const auto end = std::partition(corners.begin() + begin, corners.end(),
                                    [&](const FastCorner& c) { return c.x < x1; });
    const Node root{x0, static_cast<double>(area.y), x1, static_cast<double>(area.y + area.height),
                    begin, static_cast<int>(end - corners.begin())};
    if (root.count() > 0) nodes.push_back(root);
    begin = root.end;
  }

  std::vector<Node> next;
  while (nodes.size() < static_cast<size_t>(target)) {
    // One round: split every node with more than one corner, the fullest
    // first, stopping as soon as there are enough nodes.
    std::stable_sort(nodes.begin(), nodes.end(),
                     [](const Node& a, const Node& b) { return a.count() > b.count(); });
    if (std::none_of(nodes.begin(), nodes.end(), [](const Node& n) { return n.splittable(); })) break;
    next.clear();
    size_t n_nodes = nodes.size();
    for (const Node& node : nodes) {
      if (node.splittable() && n_nodes < static_cast<size_t>(target)) {
        const size_t before = next.size();
        Split(node, corners, next);
        n_nodes += next.size() - before - 1;
      } else {
        next.push_back(node);
      }
    }
    nodes.swap(next);
  }

  // Strongest corner per node; the weakest nodes go when there are too many.
  std::vector<FastCorner> kept;
  kept.reserve(nodes.size());
  for (const Node& node : nodes) {
    kept.push_back(*std::max_element(
        corners.begin() + node.begin, corners.begin() + node.end,
        [](const FastCorner& a, const FastCorner& b) { return a.score < b.score; }));
  }
  if (kept.size() > static_cast<size_t>(target)) {
    std::nth_element(kept.begin(), kept.begin() + target, kept.end(),
                     [](const FastCorner& a, const FastCorner& b) { return a.score > b.score; });
    kept.resize(static_cast<size_t>(target));
  }
  corners.swap(kept);
}

}  // namespace dlslam::features
