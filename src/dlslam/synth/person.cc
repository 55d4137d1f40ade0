#include "dlslam/synth/person.h"

#include <cmath>

namespace dlslam::synth {

namespace {

// Lengths at height 1.75 m [m].
constexpr double kShoulderHeightAboveHip = 0.53;
constexpr double kShoulderHalfWidth = 0.2;
constexpr double kHipHalfWidth = 0.09;
constexpr double kUpperArm = 0.30, kLowerArm = 0.27;
constexpr double kUpperLeg = 0.45, kLowerLeg = 0.40;
constexpr double kNeck = 0.2;  // torso top (shoulder line) to the head frame

SE3d Translate(double x, double y, double z) { return SE3d(SO3d(), Eigen::Vector3d(x, y, z)); }
SE3d Rotate(const Eigen::Vector3d& axis, double angle) { return SE3d(SO3d::Exp(axis * angle), Eigen::Vector3d::Zero()); }
// Flexion: rotates the limb's -z axis towards +x.
SE3d Flex(double angle) { return Rotate(Eigen::Vector3d::UnitY(), -angle); }

}  // namespace

std::vector<Mesh> BuildPersonMeshes(const PersonLook& look) {
  const float s = look.height / 1.75f;
  const float g = look.girth * s;
  std::vector<Mesh> parts(kPersonPartCount);
  AddCapsule(parts[kTorso], 0.11f * g, 0.18f * g, 0.45f * s, 0.07f * s, look.shirt, 14, 3);
  AddCapsule(parts[kHead], 0.095f * s, 0.08f * s, 0.07f * s, 0.1f * s, look.head, 14, 4);
  for (int side = 0; side < 2; ++side) {
    Mesh& upper_arm = parts[side == 0 ? kUpperArmLeft : kUpperArmRight];
    Mesh& lower_arm = parts[side == 0 ? kLowerArmLeft : kLowerArmRight];
    AddCapsule(upper_arm, 0.048f * g, 0.048f * g, static_cast<float>(kUpperArm) * s, 0.045f * g, look.shirt, 10, 2);
    AddCapsule(lower_arm, 0.04f * g, 0.04f * g, static_cast<float>(kLowerArm) * s, 0.04f * g,
               look.long_sleeves ? look.shirt : look.skin, 10, 2);
    Mesh& upper_leg = parts[side == 0 ? kUpperLegLeft : kUpperLegRight];
    Mesh& lower_leg = parts[side == 0 ? kLowerLegLeft : kLowerLegRight];
    AddCapsule(upper_leg, 0.075f * g, 0.075f * g, static_cast<float>(kUpperLeg) * s, 0.06f * g, look.trousers, 10, 2);
    AddCapsule(lower_leg, 0.055f * g, 0.055f * g, static_cast<float>(kLowerLeg) * s, 0.05f * g, look.trousers, 10, 2);
    const int m = look.shoes;
    AddBox(parts[side == 0 ? kFootLeft : kFootRight], Eigen::Vector3f(-0.05f * s, -0.045f * s, -0.07f * s),
           Eigen::Vector3f(0.2f * s, 0.045f * s, 0.0f), {m, m, m, m, m, m});
  }
  return parts;
}

std::array<SE3d, kPersonPartCount> PersonPartPoses(const PersonLook& look, const PersonPose& pose) {
  const double s = look.height / 1.75;
  std::array<SE3d, kPersonPartCount> w;
  const SE3d pelvis = pose.world_from_root * Translate(0, 0, pose.hip_height * s);
  // The torso and head extend along +z: flexing by -pitch leans them forward.
  w[kTorso] = pelvis * Rotate(Eigen::Vector3d::UnitX(), pose.torso_roll) * Flex(-pose.torso_pitch) *
              Translate(0, 0, kShoulderHeightAboveHip * s);
  w[kHead] = w[kTorso] * Translate(0, 0, kNeck * s) * Rotate(Eigen::Vector3d::UnitZ(), pose.head_yaw) *
             Flex(-pose.head_pitch);
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;  // left is +y
    const SE3d shoulder = w[kTorso] * Translate(0, sign * kShoulderHalfWidth * s, -0.03 * s) *
                          Rotate(Eigen::Vector3d::UnitX(), sign * pose.shoulder_abduction[side]) *
                          Flex(pose.shoulder[side]);
    w[side == 0 ? kUpperArmLeft : kUpperArmRight] = shoulder;
    w[side == 0 ? kLowerArmLeft : kLowerArmRight] = shoulder * Translate(0, 0, -kUpperArm * s) * Flex(pose.elbow[side]);
    const SE3d hip = pelvis * Translate(0, sign * kHipHalfWidth * s, 0) * Flex(pose.hip[side]);
    const SE3d knee = hip * Translate(0, 0, -kUpperLeg * s) * Flex(-pose.knee[side]);
    w[side == 0 ? kUpperLegLeft : kUpperLegRight] = hip;
    w[side == 0 ? kLowerLegLeft : kLowerLegRight] = knee;
    w[side == 0 ? kFootLeft : kFootRight] = knee * Translate(0, 0, -kLowerLeg * s) * Flex(pose.ankle[side]);
  }
  return w;
}

Eigen::Vector3d HandPosition(const PersonLook& look, const PersonPose& pose, int side) {
  const double s = look.height / 1.75;
  const auto w = PersonPartPoses(look, pose);
  return w[side == 0 ? kLowerArmLeft : kLowerArmRight] * Eigen::Vector3d(0, 0, -kLowerArm * s);
}

}  // namespace dlslam::synth
