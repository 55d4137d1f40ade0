#pragma once
// Where a walker is at any time: a closed route of waypoints on the floor,
// walked on straight legs. Where the walker walks through a waypoint the
// corner is rounded (it turns while walking); where it stops it slows down,
// turns on the spot towards the next leg, stands still, and speeds up again.
// A pure, periodic function of time, so any frame can be rendered on its own.

#include <Eigen/Core>

#include <vector>

namespace dlslam::synth {

struct Waypoint {
  Eigen::Vector2d position{0.0, 0.0};  // on the floor [m]
  double stand_s = 0.0;  // standing still here after turning [s]; > 0 makes it a stop
};

struct WalkRouteOptions {
  double speed = 1.0;                  // cruising speed [m/s]
  double ramp_s = 0.7;                 // speeding up after / slowing down before a stop [s]
  double turn_rate = 3.0;              // turning on the spot [rad/s]
  double corner_radius = 0.35;         // rounding of walked-through corners [m] (less on short legs)
  double max_walk_through_turn = 1.6;  // sharper corners [rad] become stops (people turn on the spot)

  // Throws dlslam::Error naming the offending value.
  void Check() const;
};

struct WalkState {
  Eigen::Vector2d position{0.0, 0.0};  // on the floor [m]
  double heading = 0.0;                // facing direction [rad] about z, 0 = +x
  double distance = 0.0;               // walked since t = 0 [m] (negative before), drives the gait
  double speed_fraction = 0.0;         // 0 standing or turning, 1 cruising
};

class WalkRoute {
 public:
  // At least two waypoints, consecutive ones (and the last and the first)
  // apart. The first waypoint is always a stop; t = 0 is the moment the
  // walker leaves it. Throws dlslam::Error on a bad route.
  WalkRoute(const std::vector<Waypoint>& waypoints, const WalkRouteOptions& options);

  double period_s() const { return period_s_; }
  double length_m() const { return length_m_; }
  // Fraction of the period spent standing or turning on the spot.
  double standing_fraction() const;
  WalkState At(double t) const;

 private:
  // A straight line (curvature 0) or a circular arc of the route.
  struct Piece {
    Eigen::Vector2d start{0.0, 0.0};
    double heading = 0.0;    // at the start [rad]
    double curvature = 0.0;  // [1/m], > 0 turns left
    double length = 0.0;     // [m]
  };
  // From one stop to the next: the pieces walked, then the turn and the stand there.
  struct Stretch {
    std::vector<Piece> pieces;
    double length = 0.0;      // [m]
    double distance_before = 0.0;  // route length walked before this stretch in a cycle [m]
    double start_s = 0.0;     // time in the cycle when the walker leaves [s]
    double ramp_s = 0.0;      // this stretch's ramp (shorter on short stretches) [s]
    double walk_s = 0.0;      // leaving to arriving [s]
    double end_heading = 0.0; // arriving [rad]
    double turn = 0.0;        // turn on the spot at the stop [rad]
    double turn_s = 0.0;
    double stand_s = 0.0;
  };
  void PlaceOnStretch(const Stretch& stretch, double distance, WalkState& state) const;

  WalkRouteOptions options_;
  std::vector<Stretch> stretches_;
  double period_s_ = 0.0;
  double length_m_ = 0.0;
};

}  // namespace dlslam::synth
