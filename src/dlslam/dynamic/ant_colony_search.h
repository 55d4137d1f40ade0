#pragma once
// The paper's "new ant colony strategy" (Sec. III-E) with the ACO rules of
// Sec. III-D; see docs/dynamic.md for the design and a sketch.
//
// Per frame: the projected points are bucketed into square cells. A path l
// over the non-empty cells is built with the Eq. 4 transition rule (pheromone
// tau^alpha times the heuristic eta^beta, eta = 1 / (1 + hop length)), from S
// = the cell with the most pheromone. Walking l, every point not yet decided
// becomes a path point m_i and is tested:
//   dynamic (or vanished) -> test every point within R of m_i, then, band by
//                            band, every point within dh of the dynamic points
//                            the last band found, until a band finds none;
//   static                -> the points within the skip radius of m_i (R,
//                            shrunk by the cell's pheromone) are not tested;
//   unknown / unreliable  -> nothing is inferred; the walk goes on.
// After the frame the pheromone evaporates (Eq. 5) and every dynamic point
// deposits on its cell (Eq. 6), so the next frame starts where movers were
// and searches there densely.

#include <opencv2/core.hpp>

#include <cstdint>
#include <random>
#include <vector>

#include "dlslam/dynamic/point_search.h"

namespace dlslam::dynamic {

class AntColonySearch final : public PointSearch {
 public:
  explicit AntColonySearch(const AntColonyOptions& options);  // checks options

  SearchResult Search(const std::vector<ProjectedPoint>& points, cv::Size image,
                      const std::function<PointLabel(std::size_t)>& test) override;

  // Pheromone per cell, row-major over grid_size() (empty before the first
  // call). Persists across calls; reset when the image size changes.
  const std::vector<double>& pheromone() const { return tau_; }
  cv::Size grid_size() const { return {grid_cols_, grid_rows_}; }
  // Cells (row-major indices) of the last call's path l, in walking order.
  const std::vector<int>& last_path() const { return path_; }
  // Path points m_i of the last call (point indices, in walking order).
  const std::vector<int>& last_path_points() const { return path_points_; }
  const AntColonyOptions& options() const { return options_; }
  // Changes the per-frame test budget (AntColonyOptions::max_tests, >= 0),
  // e.g. to follow the time left; the pheromone is kept.
  void set_max_tests(int max_tests);

 private:
  enum class State : std::uint8_t { kOpen, kSkipped, kTested };

  void ResetGrid(cv::Size image);
  void BucketPoints(const std::vector<ProjectedPoint>& points);
  void BuildPath();
  // Calls visit(j) for every point j within `radius` of `centre`, in fine
  // cells whose `per_cell` count is non-zero (cells with nothing left to do
  // are not scanned).
  template <typename Visit>
  void ForEachNear(const Eigen::Vector2f& centre, float radius, const std::vector<int>& per_cell,
                   Visit&& visit) const;
  void SetState(int point, State state);
  void UpdatePheromone(const std::vector<PointLabel>& labels);
  int CellOf(const Eigen::Vector2f& pixel) const;

  AntColonyOptions options_;
  std::mt19937 rng_;
  cv::Size image_{0, 0};
  int grid_cols_ = 0;
  int grid_rows_ = 0;
  std::vector<double> tau_;
  // Buffers reused across calls (no per-point allocation).
  const std::vector<ProjectedPoint>* points_ = nullptr;
  std::vector<int> cell_start_;   // counting sort: cell c holds cell_points_[start[c], start[c+1])
  std::vector<int> cell_points_;
  std::vector<int> point_cell_;
  // A finer grid for the radius queries (cells ~ dh wide, so a query scans
  // about 3x3 small cells instead of the path's large ones).
  int near_size_ = 16;
  int near_cols_ = 0;
  int near_rows_ = 0;
  std::vector<int> near_start_;
  std::vector<int> near_points_;
  std::vector<int> point_near_cell_;
  std::vector<int> near_untested_;  // per fine cell: points not tested yet
  std::vector<int> near_open_;      // per fine cell: points neither tested nor skipped
  std::vector<State> state_;
  std::vector<int> path_;
  std::vector<int> path_points_;
  std::vector<int> frontier_;
  std::vector<int> next_frontier_;
  std::vector<int> band_;
  std::vector<double> tau_alpha_;
  std::vector<double> eta_beta_;  // by squared hop length in cells
  std::vector<std::uint8_t> visited_;
  std::vector<int> candidates_;
  std::vector<double> weights_;
};

}  // namespace dlslam::dynamic
