#include "dlslam/synth/walk_route.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dlslam/util/check.h"

namespace dlslam::synth {
namespace {

constexpr double kPi = std::numbers::pi;

double AngleBetween(double a, double b) { return std::abs(std::remainder(a - b, 2 * kPi)); }

// A square of side 2 m walked counter-clockwise; the walker stops only at the
// first corner, where it stands 1.5 s.
std::vector<Waypoint> Square() {
  return {{{0, 0}, 1.5}, {{2, 0}, 0.0}, {{2, 2}, 0.0}, {{0, 2}, 0.0}};
}

TEST(WalkRoute, RoundsWalkedThroughCornersAndStopsWhereTold) {
  WalkRouteOptions o;
  o.speed = 1.2;
  o.ramp_s = 0.5;
  o.turn_rate = 2.0;
  o.corner_radius = 0.4;
  const WalkRoute route(Square(), o);
  // Three rounded quarter circles each save 2r - r pi / 2 of the 8 m polyline.
  const double length = 8 - 3 * (2 * 0.4 - 0.4 * kPi / 2);
  EXPECT_NEAR(route.length_m(), length, 1e-9);
  // One ramp up and one down cost half a ramp each in distance; then the
  // 90 degree turn on the spot and the stand.
  EXPECT_NEAR(route.period_s(), length / o.speed + o.ramp_s + (kPi / 2) / o.turn_rate + 1.5, 1e-9);
  EXPECT_NEAR(route.standing_fraction(), ((kPi / 2) / o.turn_rate + 1.5) / route.period_s(), 1e-9);

  // t = 0: leaving the first waypoint along +x.
  const WalkState start = route.At(0.0);
  EXPECT_LT(start.position.norm(), 1e-12);
  EXPECT_LT(AngleBetween(start.heading, 0.0), 1e-12);
  EXPECT_EQ(start.speed_fraction, 0.0);
  // Cruising along the first side: at full speed, on the line y = 0.
  const WalkState a = route.At(0.8), b = route.At(1.0);
  EXPECT_NEAR((b.position - a.position).norm() / 0.2, o.speed, 1e-9);
  EXPECT_NEAR(a.position.y(), 0.0, 1e-12);
  EXPECT_EQ(a.speed_fraction, 1.0);
  // Mid corner at (2, 0): on the arc of radius r around (2 - r, r), heading 45 degrees.
  const double arc_middle = (2 - 0.4 + 0.4 * kPi / 4) / o.speed + 0.5 * o.ramp_s;
  const WalkState corner = route.At(arc_middle);
  EXPECT_NEAR((corner.position - Eigen::Vector2d(1.6, 0.4)).norm(), 0.4, 1e-6);
  EXPECT_NEAR(corner.heading, kPi / 4, 1e-6);
  // Back at the first waypoint: it arrives facing -y, turns to +x, stands still.
  const double arrive = length / o.speed + o.ramp_s;
  const WalkState arrived = route.At(arrive + 1e-9);
  EXPECT_LT(arrived.position.norm(), 1e-6);
  EXPECT_LT(AngleBetween(arrived.heading, -kPi / 2), 1e-6);
  const WalkState turned = route.At(arrive + (kPi / 2) / o.turn_rate + 0.1);
  EXPECT_LT(AngleBetween(turned.heading, 0.0), 1e-9);
  const WalkState later = route.At(route.period_s() - 0.01);
  EXPECT_EQ(later.position, turned.position) << "standing still";
  EXPECT_EQ(later.heading, turned.heading);
  EXPECT_EQ(later.speed_fraction, 0.0);
  EXPECT_NEAR(later.distance, length, 1e-9);
}

TEST(WalkRoute, MovesContinuouslyAndPeriodically) {
  WalkRouteOptions o;
  o.speed = 0.9;
  // A rounded corner at the second waypoint; the third is sharp (> max_walk_through_turn): a stop, turning only.
  const std::vector<Waypoint> route_points = {{{-1, 1.5}, 0.7}, {{1, 1.3}, 0.0}, {{1.3, 2.0}, 0.0}, {{0.4, 2.1}, 2.0}};
  const WalkRoute route(route_points, o);
  const double dt = 1e-3;
  WalkState previous = route.At(-5.0);
  for (double t = -5.0 + dt; t < 3 * route.period_s(); t += dt) {
    const WalkState s = route.At(t);
    ASSERT_LE((s.position - previous.position).norm(), o.speed * dt * 1.001 + 1e-9) << t;
    ASSERT_LE(AngleBetween(s.heading, previous.heading), 1.5 * o.turn_rate * dt + 1e-6) << t;
    ASSERT_NEAR(s.distance - previous.distance, (s.position - previous.position).norm(), 1e-6) << t;
    ASSERT_GE(s.speed_fraction, 0.0);
    ASSERT_LE(s.speed_fraction, 1.0);
    previous = s;
  }
  for (const double t : {0.3, 2.0, 7.7}) {
    const WalkState a = route.At(t), b = route.At(t + 2 * route.period_s());
    EXPECT_LT((a.position - b.position).norm(), 1e-9) << t;
    EXPECT_NEAR(b.distance - a.distance, 2 * route.length_m(), 1e-6) << t;
  }
  // Every waypoint is visited: the stops exactly, the rounded corners closely.
  for (const Waypoint& w : route_points) {
    double closest = 1e9;
    for (double t = 0; t < route.period_s(); t += 0.01) closest = std::min(closest, (route.At(t).position - w.position).norm());
    EXPECT_LT(closest, 0.15) << w.position.transpose();
  }
}

TEST(WalkRoute, RefusesBadRoutes) {
  EXPECT_THROW(WalkRoute({{{0, 0}, 1.0}}, {}), Error);
  EXPECT_THROW(WalkRoute({{{0, 0}, 1.0}, {{0, 0.01}, 0.0}}, {}), Error);
  EXPECT_THROW(WalkRoute({{{0, 0}, 1.0}, {{1, 0}, -1.0}}, {}), Error);
  WalkRouteOptions o;
  o.speed = 0;
  EXPECT_THROW(WalkRoute(Square(), o), Error);
  o = {};
  o.turn_rate = 0;
  EXPECT_THROW(WalkRoute(Square(), o), Error);
}

}  // namespace
}  // namespace dlslam::synth
