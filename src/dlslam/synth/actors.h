#pragma once
// Things that move: people walking a route (some carrying a box), people
// sitting and gesturing, a box slid across a desk. Each is a set of rigid
// parts whose poses are a pure function of the scene time, so any frame can
// be rendered on its own and the motion between any two times is known.

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

#include "dlslam/geometry/se3.h"
#include "dlslam/synth/mesh.h"
#include "dlslam/synth/person.h"
#include "dlslam/synth/walk_route.h"

namespace dlslam::synth {

// Ground-truth classes of the masks.
inline constexpr int kClassStatic = 0;
inline constexpr int kClassPerson = 1;
inline constexpr int kClassMovable = 2;  // other movable object

struct ActorPart {
  Mesh mesh;  // in the part frame
  int class_id = kClassPerson;
};

struct Actor {
  std::string kind;  // "walker", "sitter", "sliding box"
  std::vector<ActorPart> parts;
  // world_from_part of every part at scene time t [s] (any t, also < 0).
  std::function<std::vector<SE3d>(double t)> pose_at;
};

struct WalkerParams {
  std::vector<Waypoint> route = {{{-1.0, 1.6}, 1.0}, {{1.0, 1.6}, 1.0}};  // closed, on the floor (WalkRoute)
  WalkRouteOptions walk;            // pace and turning
  double schedule_offset_s = 0.0;   // route time at scene time 0 [s]
  double look_around_phase = 0.0;   // of the head's slow turning [rad]
  bool carry_box = false;           // holds a box (class 2) in front
  int box_material = 0;
};
// How far in front of the root a walker holds a carried box [m] at height 1.75 (scaled).
inline constexpr double kCarriedBoxAhead = 0.36;
Actor MakeWalker(const PersonLook& look, const WalkerParams& params);

struct SitterParams {
  Eigen::Vector2d seat{0.0, 2.45};  // root position on the floor [m]
  double heading = 0.0;             // [rad] about z; 0 faces +x
  double seat_height = 0.47;        // [m]
  std::vector<double> gesture_times;  // start of each arm gesture [s]
  double gesture_duration_s = 1.6;
  double phase = 0.0;               // of the slow sway [rad]
};
Actor MakeSitter(const PersonLook& look, const SitterParams& params);

struct SlidingBoxParams {
  Eigen::Vector3d start{0.1, 1.7, 0.75};  // bottom centre at rest [m]
  Eigen::Vector3d travel{0.3, 0.0, 0.0};  // displacement of one slide [m]
  Eigen::Vector3d size{0.26, 0.2, 0.12};  // [m]
  double rest_s = 3.5;                    // still between slides [s]
  double slide_s = 1.5;                   // duration of one slide [s]
  double offset_s = 0.0;                  // schedule shift [s]
  int material = 0;
};
Actor MakeSlidingBox(const SlidingBoxParams& params);

// Smooth 0 -> 1 on [0, 1] (3x^2 - 2x^3), clamped outside.
double SmoothStep(double x);

}  // namespace dlslam::synth
