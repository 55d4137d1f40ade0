#pragma once
// An articulated person of capsules and boxes: torso, head, upper and lower
// arms, upper and lower legs, feet. The pose is a root on the floor plus
// joint angles; forward kinematics gives every part's pose in the world.

#include <array>
#include <vector>

#include "dlslam/geometry/se3.h"
#include "dlslam/synth/mesh.h"

namespace dlslam::synth {

enum PersonPart {
  kTorso, kHead,
  kUpperArmLeft, kLowerArmLeft, kUpperArmRight, kLowerArmRight,
  kUpperLegLeft, kLowerLegLeft, kFootLeft, kUpperLegRight, kLowerLegRight, kFootRight,
  kPersonPartCount
};

struct PersonLook {
  float height = 1.75f;  // [m] standing; every length scales with it
  float girth = 1.0f;    // width/depth multiplier of torso and limbs
  // Material indices (Scene::materials).
  int shirt = 0, trousers = 0, head = 0, skin = 0, shoes = 0;
  bool long_sleeves = true;  // lower arms in the shirt material, else skin
};

// Joint angles [rad]; flexion > 0 swings a limb forward (the knee bends back).
// Index 0 is the left side, 1 the right.
struct PersonPose {
  SE3d world_from_root;        // root on the floor: x forward, y left, z up
  double hip_height = 0.92;    // hip joints above the root [m] at height 1.75 (scaled)
  double torso_pitch = 0.0;    // forward lean
  double torso_roll = 0.0;     // sideways lean
  double head_yaw = 0.0;       // left > 0
  double head_pitch = 0.0;     // nodding down > 0
  std::array<double, 2> hip{}, knee{}, ankle{};
  std::array<double, 2> shoulder{}, shoulder_abduction{}, elbow{};
};

// One mesh per part, each in its part frame (joint at the origin, limb along -z).
std::vector<Mesh> BuildPersonMeshes(const PersonLook& look);

// world_from_part for every part of the meshes above.
std::array<SE3d, kPersonPartCount> PersonPartPoses(const PersonLook& look, const PersonPose& pose);

// Where the hands are (end of the lower arms), for things held.
Eigen::Vector3d HandPosition(const PersonLook& look, const PersonPose& pose, int side);

}  // namespace dlslam::synth
