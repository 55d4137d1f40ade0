#include "dlslam/synth/walk_route.h"

#include <algorithm>
#include <cmath>

#include "dlslam/synth/actors.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

Eigen::Vector2d Direction(double heading) { return {std::cos(heading), std::sin(heading)}; }

}  // namespace

void WalkRouteOptions::Check() const {
  DLSLAM_CHECK(speed > 0 && speed < 5, "walking speed {} m/s outside (0, 5)", speed);
  DLSLAM_CHECK_GE(ramp_s, 0.0, "speed ramp [s]");
  DLSLAM_CHECK_GT(turn_rate, 0.0, "turn rate [rad/s]");
  DLSLAM_CHECK_GE(corner_radius, 0.0, "corner radius [m]");
  DLSLAM_CHECK(max_walk_through_turn >= 0 && max_walk_through_turn < 3.1,
               "largest walked-through turn {} rad outside [0, 3.1)", max_walk_through_turn);
}

WalkRoute::WalkRoute(const std::vector<Waypoint>& waypoints, const WalkRouteOptions& options) : options_(options) {
  options_.Check();
  const int n = static_cast<int>(waypoints.size());
  DLSLAM_CHECK_GE(n, 2, "waypoints of a walking route");
  auto at = [&](int i) -> const Waypoint& { return waypoints[static_cast<std::size_t>((i + n) % n)]; };
  std::vector<double> leg_heading(static_cast<std::size_t>(n)), leg_length(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d d = at(i + 1).position - at(i).position;
    DLSLAM_CHECK(d.norm() > 0.05, "waypoints {} and {} of the walking route are {} m apart (at least 0.05)", i,
                 (i + 1) % n, d.norm());
    DLSLAM_CHECK_GE(at(i).stand_s, 0.0, "standing time [s] at waypoint {}", i);
    leg_heading[static_cast<std::size_t>(i)] = std::atan2(d.y(), d.x());
    leg_length[static_cast<std::size_t>(i)] = d.norm();
  }
  auto leg = [&](const std::vector<double>& v, int i) { return v[static_cast<std::size_t>((i + n) % n)]; };
  // At waypoint i the walker turns from leg i - 1 to leg i.
  std::vector<double> turn(static_cast<std::size_t>(n)), tangent(static_cast<std::size_t>(n), 0.0),
      radius(static_cast<std::size_t>(n), 0.0);
  std::vector<bool> stop(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    turn[k] = WrapAngle(leg(leg_heading, i) - leg(leg_heading, i - 1));
    stop[k] = i == 0 || at(i).stand_s > 0 || std::abs(turn[k]) > options_.max_walk_through_turn;
    if (stop[k] || std::abs(turn[k]) < 1e-9 || options_.corner_radius == 0) continue;
    const double half_tan = std::tan(0.5 * std::abs(turn[k]));
    tangent[k] = std::min(options_.corner_radius * half_tan,
                          0.45 * std::min(leg(leg_length, i - 1), leg(leg_length, i)));
    radius[k] = tangent[k] / half_tan;
  }

  Stretch current;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const auto ki = static_cast<std::size_t>(i), kj = static_cast<std::size_t>(j);
    const Eigen::Vector2d dir = Direction(leg_heading[ki]);
    current.pieces.push_back({at(i).position + tangent[ki] * dir, leg_heading[ki], 0.0,
                              leg_length[ki] - tangent[ki] - tangent[kj]});
    if (stop[kj]) {
      current.end_heading = leg_heading[ki];
      current.turn = turn[kj];
      current.stand_s = at(j).stand_s;
      stretches_.push_back(std::move(current));
      current = {};
    } else if (tangent[kj] > 0) {
      current.pieces.push_back({at(j).position - tangent[kj] * dir, leg_heading[ki],
                                (turn[kj] > 0 ? 1.0 : -1.0) / radius[kj], radius[kj] * std::abs(turn[kj])});
    }
  }
  for (Stretch& s : stretches_) {
    s.length = 0;
    for (const Piece& p : s.pieces) s.length += p.length;
    s.distance_before = length_m_;
    s.start_s = period_s_;
    s.ramp_s = std::min(options_.ramp_s, s.length / options_.speed);
    s.walk_s = s.ramp_s + s.length / options_.speed;
    s.turn_s = std::abs(s.turn) / options_.turn_rate;
    length_m_ += s.length;
    period_s_ += s.walk_s + s.turn_s + s.stand_s;
  }
}

double WalkRoute::standing_fraction() const {
  double standing = 0;
  for (const Stretch& s : stretches_) standing += s.turn_s + s.stand_s;
  return standing / period_s_;
}

void WalkRoute::PlaceOnStretch(const Stretch& stretch, double distance, WalkState& state) const {
  for (std::size_t k = 0; k < stretch.pieces.size(); ++k) {
    const Piece& p = stretch.pieces[k];
    if (distance > p.length && k + 1 < stretch.pieces.size()) {
      distance -= p.length;
      continue;
    }
    const double u = std::clamp(distance, 0.0, p.length);
    if (p.curvature == 0) {
      state.position = p.start + u * Direction(p.heading);
      state.heading = p.heading;
    } else {
      const double h = p.heading + p.curvature * u;
      state.position = p.start + Eigen::Vector2d(std::sin(h) - std::sin(p.heading), std::cos(p.heading) - std::cos(h)) /
                                     p.curvature;
      state.heading = h;
    }
    return;
  }
}

WalkState WalkRoute::At(double t) const {
  const double cycles = std::floor(t / period_s_);
  const double tau = t - cycles * period_s_;
  std::size_t k = 0;
  while (k + 1 < stretches_.size() && stretches_[k + 1].start_s <= tau) ++k;
  const Stretch& s = stretches_[k];
  const double local = tau - s.start_s;
  WalkState state;
  state.distance = cycles * length_m_ + s.distance_before;
  if (local < s.walk_s) {
    // Smooth-step speed profile: ramp up, cruise, ramp down (integrals in closed form).
    const double r = s.ramp_s, v = options_.speed, cruise = s.walk_s - 2 * r;
    auto ramp_integral = [](double x) { return x * x * x - 0.5 * x * x * x * x; };
    double d;
    if (local < r) {
      const double x = local / r;
      d = v * r * ramp_integral(x);
      state.speed_fraction = SmoothStep(x);
    } else if (local < r + cruise) {
      d = v * (local - 0.5 * r);
      state.speed_fraction = 1.0;
    } else {
      const double x = (local - r - cruise) / r;
      d = v * (0.5 * r + cruise + r * (x - ramp_integral(x)));
      state.speed_fraction = 1.0 - SmoothStep(x);
    }
    PlaceOnStretch(s, d, state);
    state.distance += d;
    return state;
  }
  PlaceOnStretch(s, s.length, state);
  state.distance += s.length;
  const double turned = s.turn_s > 0 ? SmoothStep((local - s.walk_s) / s.turn_s) : 1.0;
  state.heading = s.end_heading + turned * s.turn;
  return state;
}

}  // namespace dlslam::synth
