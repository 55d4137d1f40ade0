#include "dlslam/synth/walker_routes.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "dlslam/synth/random.h"
#include "dlslam/synth/room.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {

constexpr double kGapStep_s = 0.04;   // time step of the gap check
constexpr double kMinLeg_m = 0.5;     // consecutive waypoints at least this far apart
constexpr double kViewCone = 0.5;     // |x| < kViewCone * y: in the start view (its edge is at 0.6 y)
constexpr int kOffsetCandidates = 32;  // schedule offsets tried for the second walker
constexpr int kMaxAttempts = 500;

double InViewFraction(const WalkRoute& route) {
  int in = 0, n = 0;
  for (double t = 0; t < route.period_s(); t += 0.1, ++n) {
    const Eigen::Vector2d p = route.At(t).position;
    in += std::abs(p.x()) < kViewCone * p.y() ? 1 : 0;
  }
  return static_cast<double>(in) / n;
}

bool LegsLongEnough(const std::vector<Waypoint>& route) {
  for (std::size_t i = 0; i < route.size(); ++i) {
    if ((route[i].position - route[(i + 1) % route.size()].position).norm() < kMinLeg_m) return false;
  }
  return true;
}

// A loop around the zone's centre with waypoints at increasing angles (so it
// never crosses itself): a near side across the view, a far side back, legs
// towards and away from the camera in between, some waypoints out of view.
std::vector<Waypoint> RandomLoop(std::mt19937& rng, const WalkerPairOptions& o) {
  const Eigen::Vector2d centre = 0.5 * (room::kWalkZoneMin + room::kWalkZoneMax);
  const Eigen::Vector2d half = 0.5 * (room::kWalkZoneMax - room::kWalkZoneMin);
  const int n = UniformInt(rng, 4, 6);
  const double first_angle = Uniform(rng, 0.0, 2 * std::numbers::pi);
  std::vector<Waypoint> route;
  for (int i = 0; i < n; ++i) {
    const double a = first_angle + 2 * std::numbers::pi * (i + Uniform(rng, 0.15, 0.85)) / n;
    const double reach_x = Uniform01(rng) < o.exit_probability ? Uniform(rng, 0.82, 1.0) * half.x()
                                                                : Uniform(rng, 0.25, 0.55) * half.x();
    Waypoint w;
    w.position = centre + Eigen::Vector2d(reach_x * std::cos(a), Uniform(rng, 0.85, 1.0) * half.y() * std::sin(a));
    w.stand_s = (i == 0 || Uniform01(rng) < o.stand_probability) ? Uniform(rng, 0.5, 2.0) : 0.0;
    route.push_back(w);
  }
  return route;
}

// Footprints on the floor: the body, and the box carried in front.
struct Footprint {
  Eigen::Vector2d centre;
  double radius;
};

}  // namespace

void WalkerPairOptions::Check() const {
  DLSLAM_CHECK_GT(body_radius, 0.0, "body radius [m]");
  DLSLAM_CHECK_GT(box_radius, 0.0, "box radius [m]");
  DLSLAM_CHECK_GE(clearance, 0.0, "clearance [m]");
  DLSLAM_CHECK(min_in_view_fraction >= 0 && min_in_view_fraction <= 0.9, "in-view fraction {} outside [0, 0.9]",
               min_in_view_fraction);
  DLSLAM_CHECK(exit_probability >= 0 && exit_probability <= 0.5, "exit probability {} outside [0, 0.5]",
               exit_probability);
  DLSLAM_CHECK(stand_probability >= 0 && stand_probability <= 1, "stand probability {} outside [0, 1]",
               stand_probability);
}

double SmallestGap(const std::array<WalkerParams, 2>& walkers, const WalkerPairOptions& options) {
  const std::array<WalkRoute, 2> routes = {WalkRoute(walkers[0].route, walkers[0].walk),
                                           WalkRoute(walkers[1].route, walkers[1].walk)};
  const double period = std::max(routes[0].period_s(), routes[1].period_s());
  const double box_ahead = kCarriedBoxAhead * 1.9 / 1.75;  // the tallest person's
  double gap = std::numeric_limits<double>::infinity();
  for (double t = 0; t < period; t += kGapStep_s) {
    std::array<std::vector<Footprint>, 2> feet;
    for (std::size_t k = 0; k < 2; ++k) {
      const WalkState w = routes[k].At(t + walkers[k].schedule_offset_s);
      feet[k].push_back({w.position, options.body_radius});
      if (walkers[k].carry_box) {
        feet[k].push_back({w.position + box_ahead * Eigen::Vector2d(std::cos(w.heading), std::sin(w.heading)),
                           options.box_radius});
      }
    }
    for (const Footprint& a : feet[0]) {
      for (const Footprint& b : feet[1]) gap = std::min(gap, (a.centre - b.centre).norm() - a.radius - b.radius);
    }
  }
  return gap;
}

std::array<WalkerParams, 2> MakeWalkerPair(std::mt19937& rng, const WalkerPairOptions& options) {
  options.Check();
  double best_gap = -std::numeric_limits<double>::infinity();
  int short_legs = 0, out_of_view = 0;
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    // Both walk the same loop at the same pace, about half a loop apart (two
    // free routes in so small a floor would meet sooner or later).
    std::array<WalkerParams, 2> w;
    w[0].route = RandomLoop(rng, options);
    w[0].walk.speed = Uniform(rng, 0.8, 1.2);
    if (!LegsLongEnough(w[0].route)) {
      ++short_legs;
      continue;
    }
    const WalkRoute route(w[0].route, w[0].walk);
    if (InViewFraction(route) < options.min_in_view_fraction) {
      ++out_of_view;
      continue;
    }
    w[1] = w[0];
    w[1].carry_box = true;
    for (WalkerParams& p : w) p.look_around_phase = Uniform(rng, 0.0, 2 * std::numbers::pi);
    const double period = route.period_s();
    w[0].schedule_offset_s = Uniform(rng, 0.0, period);
    best_gap = -std::numeric_limits<double>::infinity();
    double best_offset = 0;
    for (int k = -kOffsetCandidates / 4; k <= kOffsetCandidates / 4; ++k) {
      w[1].schedule_offset_s = w[0].schedule_offset_s + period * (0.5 + static_cast<double>(k) / kOffsetCandidates);
      if (const double gap = SmallestGap(w, options); gap > best_gap) {
        best_gap = gap;
        best_offset = w[1].schedule_offset_s;
      }
    }
    w[1].schedule_offset_s = best_offset;
    if (best_gap >= options.clearance) return w;
  }
  throw Error(fmt::format("no walking loop keeps two walkers {} m apart after {} attempts ({} with short legs, {} "
                          "mostly out of view; best gap {:.3f} m)",
                          options.clearance, kMaxAttempts, short_legs, out_of_view, best_gap));
}

}  // namespace dlslam::synth
