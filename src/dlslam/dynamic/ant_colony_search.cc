#include "dlslam/dynamic/ant_colony_search.h"

#include <algorithm>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {

void AntColonyOptions::Check() const {
  DLSLAM_CHECK(search_radius_px > 0 && search_radius_px <= 500,
               "AntColonyOptions::search_radius_px {} outside (0, 500]", search_radius_px);
  DLSLAM_CHECK(static_skip_radius_px >= 0 && static_skip_radius_px <= 500,
               "AntColonyOptions::static_skip_radius_px {} outside [0, 500]",
               static_skip_radius_px);
  DLSLAM_CHECK(band_width_px > 0 && band_width_px <= 500,
               "AntColonyOptions::band_width_px {} outside (0, 500]", band_width_px);
  DLSLAM_CHECK(alpha >= 0 && alpha <= 10, "AntColonyOptions::alpha {} outside [0, 10]", alpha);
  DLSLAM_CHECK(beta >= 0 && beta <= 10, "AntColonyOptions::beta {} outside [0, 10]", beta);
  DLSLAM_CHECK(q0 >= 0 && q0 <= 1, "AntColonyOptions::q0 {} outside [0, 1]", q0);
  DLSLAM_CHECK(rho >= 0 && rho < 1, "AntColonyOptions::rho {} outside [0, 1)", rho);
  DLSLAM_CHECK(deposit >= 0 && deposit <= 1000, "AntColonyOptions::deposit {} outside [0, 1000]",
               deposit);
  DLSLAM_CHECK(tau_min > 0 && tau_min <= tau_max,
               "AntColonyOptions: need 0 < tau_min {} <= tau_max {}", tau_min, tau_max);
  DLSLAM_CHECK(tau_max <= 1e6, "AntColonyOptions::tau_max {} > 1e6", tau_max);
  DLSLAM_CHECK(cell_size_px >= 16 && cell_size_px <= 1024,
               "AntColonyOptions::cell_size_px {} outside [16, 1024]", cell_size_px);
  DLSLAM_CHECK_GE(max_tests, 0, "AntColonyOptions::max_tests (0 = no limit)");
}

std::unique_ptr<PointSearch> MakeAntColonySearch(const AntColonyOptions& options) {
  return std::make_unique<AntColonySearch>(options);
}

AntColonySearch::AntColonySearch(const AntColonyOptions& options)
    : options_(options), rng_(options.seed) {
  options_.Check();
}

void AntColonySearch::set_max_tests(int max_tests) {
  DLSLAM_CHECK_GE(max_tests, 0, "AntColonySearch::set_max_tests (0 = no limit)");
  options_.max_tests = max_tests;
}

void AntColonySearch::ResetGrid(cv::Size image) {
  image_ = image;
  const int size = options_.cell_size_px;
  grid_cols_ = std::max(1, (image.width + size - 1) / size);
  grid_rows_ = std::max(1, (image.height + size - 1) / size);
  tau_.assign(static_cast<std::size_t>(grid_cols_) * grid_rows_, options_.tau_min);
  near_size_ = std::clamp(static_cast<int>(std::ceil(options_.band_width_px)), 8, size);
  near_cols_ = std::max(1, (image.width + near_size_ - 1) / near_size_);
  near_rows_ = std::max(1, (image.height + near_size_ - 1) / near_size_);
  const int max_hop2 = (grid_cols_ - 1) * (grid_cols_ - 1) + (grid_rows_ - 1) * (grid_rows_ - 1);
  eta_beta_.resize(static_cast<std::size_t>(max_hop2) + 1);
  for (int d2 = 0; d2 <= max_hop2; ++d2) {
    eta_beta_[static_cast<std::size_t>(d2)] =
        std::pow(1.0 / (1.0 + std::sqrt(static_cast<double>(d2))), options_.beta);
  }
}

int AntColonySearch::CellOf(const Eigen::Vector2f& pixel) const {
  const float size = static_cast<float>(options_.cell_size_px);
  const int cx = std::clamp(static_cast<int>(std::floor(pixel.x() / size)), 0, grid_cols_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor(pixel.y() / size)), 0, grid_rows_ - 1);
  return cy * grid_cols_ + cx;
}

void AntColonySearch::BucketPoints(const std::vector<ProjectedPoint>& points) {
  const std::size_t cells = tau_.size();
  cell_start_.assign(cells + 1, 0);
  point_cell_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    point_cell_[i] = CellOf(points[i].pixel);
    ++cell_start_[static_cast<std::size_t>(point_cell_[i]) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_points_.resize(points.size());
  // Fill with a running cursor per cell; input order kept inside a cell.
  candidates_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = static_cast<std::size_t>(point_cell_[i]);
    cell_points_[static_cast<std::size_t>(candidates_[c]++)] = static_cast<int>(i);
  }
  // The same counting sort on the fine grid.
  const auto near_cells = static_cast<std::size_t>(near_cols_) * near_rows_;
  near_start_.assign(near_cells + 1, 0);
  const float near = static_cast<float>(near_size_);
  const auto near_cell = [&](const Eigen::Vector2f& pixel) {
    const int cx = std::clamp(static_cast<int>(std::floor(pixel.x() / near)), 0, near_cols_ - 1);
    const int cy = std::clamp(static_cast<int>(std::floor(pixel.y() / near)), 0, near_rows_ - 1);
    return static_cast<std::size_t>(cy * near_cols_ + cx);
  };
  point_near_cell_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    point_near_cell_[i] = static_cast<int>(near_cell(points[i].pixel));
    ++near_start_[static_cast<std::size_t>(point_near_cell_[i]) + 1];
  }
  near_untested_.resize(near_cells);
  for (std::size_t c = 0; c < near_cells; ++c) near_untested_[c] = near_start_[c + 1];
  near_open_ = near_untested_;
  for (std::size_t c = 0; c < near_cells; ++c) near_start_[c + 1] += near_start_[c];
  candidates_.assign(near_start_.begin(), near_start_.end() - 1);
  near_points_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto c = static_cast<std::size_t>(point_near_cell_[i]);
    near_points_[static_cast<std::size_t>(candidates_[c]++)] = static_cast<int>(i);
  }
}

void AntColonySearch::BuildPath() {
  path_.clear();
  const int cells = static_cast<int>(tau_.size());
  candidates_.clear();  // the non-empty cells, row-major
  for (int c = 0; c < cells; ++c) {
    if (cell_start_[static_cast<std::size_t>(c) + 1] > cell_start_[static_cast<std::size_t>(c)]) {
      candidates_.push_back(c);
    }
  }
  if (candidates_.empty()) return;
  tau_alpha_.resize(tau_.size());
  int current = candidates_.front();
  for (const int c : candidates_) {
    tau_alpha_[static_cast<std::size_t>(c)] = std::pow(tau_[static_cast<std::size_t>(c)],
                                                       options_.alpha);
    // S: the strongest pheromone (first in row-major order on ties).
    if (tau_[static_cast<std::size_t>(c)] > tau_[static_cast<std::size_t>(current)]) current = c;
  }
  visited_.assign(tau_.size(), 0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  weights_.resize(candidates_.size());
  for (;;) {
    path_.push_back(current);
    visited_[static_cast<std::size_t>(current)] = 1;
    if (path_.size() == candidates_.size()) break;
    // Eq. 4 over the cells not yet on the path (allowed_m).
    const int cx = current % grid_cols_;
    const int cy = current / grid_cols_;
    double total = 0.0;
    double best_weight = -1.0;
    int best = -1;
    for (std::size_t k = 0; k < candidates_.size(); ++k) {
      const int c = candidates_[k];
      double w = 0.0;
      if (!visited_[static_cast<std::size_t>(c)]) {
        const int dx = c % grid_cols_ - cx;
        const int dy = c / grid_cols_ - cy;
        w = tau_alpha_[static_cast<std::size_t>(c)] *
            eta_beta_[static_cast<std::size_t>(dx * dx + dy * dy)];
        if (w > best_weight) {
          best_weight = w;
          best = c;
        }
      }
      total += w;
      weights_[k] = total;  // cumulative, for roulette selection
    }
    int next = best;
    if (options_.q0 < 1.0 && uniform(rng_) >= options_.q0 && total > 0.0) {
      const double r = uniform(rng_) * total;
      const auto k = static_cast<std::size_t>(
          std::upper_bound(weights_.begin(), weights_.end(), r) - weights_.begin());
      if (k < candidates_.size() && !visited_[static_cast<std::size_t>(candidates_[k])]) {
        next = candidates_[k];
      }
    }
    current = next;
  }
}

void AntColonySearch::SetState(int point, State state) {
  const auto i = static_cast<std::size_t>(point);
  const auto c = static_cast<std::size_t>(point_near_cell_[i]);
  if (state_[i] == State::kOpen) --near_open_[c];
  if (state == State::kTested) --near_untested_[c];
  state_[i] = state;
}

template <typename Visit>
void AntColonySearch::ForEachNear(const Eigen::Vector2f& centre, float radius,
                                  const std::vector<int>& per_cell, Visit&& visit) const {
  const float size = static_cast<float>(near_size_);
  const int x0 = std::clamp(static_cast<int>(std::floor((centre.x() - radius) / size)), 0,
                            near_cols_ - 1);
  const int x1 = std::clamp(static_cast<int>(std::floor((centre.x() + radius) / size)), 0,
                            near_cols_ - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor((centre.y() - radius) / size)), 0,
                            near_rows_ - 1);
  const int y1 = std::clamp(static_cast<int>(std::floor((centre.y() + radius) / size)), 0,
                            near_rows_ - 1);
  const float radius2 = radius * radius;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const auto c = static_cast<std::size_t>(y * near_cols_ + x);
      if (per_cell[c] == 0) continue;
      for (int k = near_start_[c]; k < near_start_[c + 1]; ++k) {
        const int j = near_points_[static_cast<std::size_t>(k)];
        if (((*points_)[static_cast<std::size_t>(j)].pixel - centre).squaredNorm() <= radius2) {
          visit(j);
        }
      }
    }
  }
}

void AntColonySearch::UpdatePheromone(const std::vector<PointLabel>& labels) {
  for (double& t : tau_) t *= 1.0 - options_.rho;  // Eq. 5, evaporation
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const bool motion = labels[i] == PointLabel::kDynamic ||
                        (options_.expand_on_vanished && labels[i] == PointLabel::kVanished);
    if (motion) tau_[static_cast<std::size_t>(point_cell_[i])] += options_.deposit;  // Eq. 6
  }
  for (double& t : tau_) t = std::clamp(t, options_.tau_min, options_.tau_max);
}

SearchResult AntColonySearch::Search(const std::vector<ProjectedPoint>& points, cv::Size image,
                                     const std::function<PointLabel(std::size_t)>& test) {
  DLSLAM_CHECK(image.width > 0 && image.height > 0, "AntColonySearch: empty image size {}x{}",
               image.width, image.height);
  if (image != image_) ResetGrid(image);
  points_ = &points;
  BucketPoints(points);
  BuildPath();

  SearchResult result;
  result.labels.assign(points.size(), PointLabel::kUntested);
  state_.assign(points.size(), State::kOpen);
  path_points_.clear();
  const int budget = options_.max_tests > 0 ? options_.max_tests : static_cast<int>(points.size());
  const auto is_motion = [this](PointLabel label) {
    return label == PointLabel::kDynamic ||
           (options_.expand_on_vanished && label == PointLabel::kVanished);
  };
  // Tests point j (once); true if it shows motion.
  const auto run_test = [&](int j) {
    const auto index = static_cast<std::size_t>(j);
    SetState(j, State::kTested);
    result.labels[index] = test(index);
    ++result.tested;
    return is_motion(result.labels[index]);
  };
  const float radius = static_cast<float>(options_.search_radius_px);
  const float band = static_cast<float>(options_.band_width_px);

  for (const int cell : path_) {
    const auto c = static_cast<std::size_t>(cell);
    for (int k = cell_start_[c]; k < cell_start_[c + 1] && result.tested < budget; ++k) {
      const int m = cell_points_[static_cast<std::size_t>(k)];
      if (state_[static_cast<std::size_t>(m)] != State::kOpen) continue;
      path_points_.push_back(m);
      const Eigen::Vector2f centre = points[static_cast<std::size_t>(m)].pixel;
      if (run_test(m)) {
        // Expand: everything within R, then bands of width dh around the
        // dynamic points each band adds, until a band adds none.
        frontier_.assign(1, m);
        float reach = radius;
        while (!frontier_.empty() && result.tested < budget) {
          next_frontier_.clear();
          for (const int f : frontier_) {
            ForEachNear(points[static_cast<std::size_t>(f)].pixel, reach, near_untested_,
                        [&](int j) {
              if (state_[static_cast<std::size_t>(j)] != State::kTested && result.tested < budget &&
                  run_test(j)) {
                next_frontier_.push_back(j);
              }
            });
          }
          frontier_.swap(next_frontier_);
          reach = band;
        }
      } else if (result.labels[static_cast<std::size_t>(m)] == PointLabel::kStatic) {
        // Skip the static group; pheromone (recent motion) shrinks the group.
        const float skip = static_cast<float>(options_.static_skip_radius_px *
                                              options_.tau_min / tau_[c]);
        ForEachNear(centre, skip, near_open_, [&](int j) {
          if (state_[static_cast<std::size_t>(j)] == State::kOpen) SetState(j, State::kSkipped);
        });
      }
    }
  }
  UpdatePheromone(result.labels);
  points_ = nullptr;
  return result;
}

}  // namespace dlslam::dynamic
