#pragma once
// The static room: walls, floor, ceiling and furniture (a desk with things on
// it, book shelves, a cabinet, a side desk, stacked boxes, picture frames,
// chairs). Its layout is fixed so that tests and the replay alignment can
// rely on it; textures and small items vary with the seed.

#include <Eigen/Core>

#include <random>

namespace dlslam::synth {

struct Scene;

namespace room {
// Inside of the walls [m] (world frame: x right, y into the room, z up).
inline const Eigen::Vector3d kMin(-3.0, -2.5, 0.0);
inline const Eigen::Vector3d kMax(3.0, 3.4, 2.8);
// The main desk the camera looks at; its top is at kDeskMax.z().
inline const Eigen::Vector3d kDeskMin(-1.0, 1.3, 0.0);
inline const Eigen::Vector3d kDeskMax(1.0, 2.1, 0.75);
// Where every camera path starts: 1.45 m high, looking along +y, pitched down.
inline const Eigen::Vector3d kViewpoint(0.0, 0.0, 1.45);
inline constexpr double kViewpointPitchDown = 0.21;  // [rad] (12 deg, as TUM fr3's start)
// The loop preset's circle at the viewpoint's height: its centre is near the
// room's, so that looking outward the walls are 1.75-2.2 m away (far enough
// for the wall textures not to be magnified, near enough for good depth).
inline const Eigen::Vector2d kLoopCentre(0.0, 0.25);
inline constexpr double kLoopRadius = 1.0;  // [m]
// Seats of the chairs behind the desk (sitting presets), facing the camera.
inline const Eigen::Vector2d kSeatLeft(-0.45, 2.45);
inline const Eigen::Vector2d kSeatRight(0.45, 2.45);
inline constexpr double kSeatHeight = 0.47;
// Walking presets: the desk and what stands on it are this much further back
// (desk front at y = 2.55 m), leaving the people a floor in front of it, as in
// TUM fr3 where they walk between the camera and the desk.
inline constexpr double kWalkingDeskShift = 1.25;  // [m] along +y
// The floor the walkers' routes (their roots) keep to in the walking presets:
// 1.2-2.05 m ahead of the start, clear of the desk and the furniture at the sides.
inline const Eigen::Vector2d kWalkZoneMin(-1.75, 1.2);
inline const Eigen::Vector2d kWalkZoneMax(1.75, 2.05);
}  // namespace room

struct RoomOptions {
  bool ceiling = true;         // close the room at the top
  bool chairs_at_desk = true;  // two chairs behind the desk (else beside the side desk)
  double desk_shift_y = 0.0;   // [m] moves the main desk and its things away from the start (+y)
};

// Adds the room's meshes, textures, materials and obstacles to `scene`.
void BuildRoom(Scene& scene, const RoomOptions& options, std::mt19937& rng);

}  // namespace dlslam::synth
