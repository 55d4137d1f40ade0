#include "dlslam/synth/actors.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

namespace dlslam::synth {

namespace {

constexpr double kPi = std::numbers::pi;

SE3d RootPose(double x, double y, double heading) {
  return SE3d(SO3d::Exp(Eigen::Vector3d(0, 0, heading)), Eigen::Vector3d(x, y, 0));
}

std::vector<ActorPart> PersonParts(const PersonLook& look) {
  std::vector<ActorPart> parts;
  for (Mesh& m : BuildPersonMeshes(look)) parts.push_back({std::move(m), kClassPerson});
  return parts;
}

std::vector<SE3d> ToVector(const std::array<SE3d, kPersonPartCount>& poses) {
  return std::vector<SE3d>(poses.begin(), poses.end());
}

}  // namespace

double SmoothStep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

Actor MakeWalker(const PersonLook& look, const WalkerParams& params) {
  Actor actor;
  actor.kind = "walker";
  actor.parts = PersonParts(look);
  const Eigen::Vector3f half(0.15f, 0.2f, 0.15f);
  if (params.carry_box) {
    ActorPart box{{}, kClassMovable};
    const int m = params.box_material;
    AddBox(box.mesh, -half, half, {m, m, m, m, m, m});
    actor.parts.push_back(std::move(box));
  }
  const auto route = std::make_shared<const WalkRoute>(params.route, params.walk);
  actor.pose_at = [look, params, route](double t) {
    const WalkState w = route->At(t + params.schedule_offset_s);
    const double g = w.speed_fraction;
    const double s = look.height / 1.75;
    const double phase = 2 * kPi * w.distance / (1.4 * s);  // one gait cycle = two steps
    PersonPose pose;
    pose.world_from_root = RootPose(w.position.x(), w.position.y(), w.heading);
    pose.hip_height = 0.92 - g * 0.012 * (1 - std::cos(2 * phase));
    pose.torso_pitch = 0.05 * g;
    // Standing people look around more than walking ones.
    pose.head_yaw = (0.12 + 0.25 * (1 - g)) * std::sin(0.35 * t + params.look_around_phase);
    pose.head_pitch = 0.08;
    for (int side = 0; side < 2; ++side) {
      const double leg = phase + side * kPi;
      pose.hip[side] = g * 0.4 * std::sin(leg);
      const double swing = std::max(0.0, std::cos(leg + 0.4));
      pose.knee[side] = 0.05 + g * (0.08 + 0.75 * swing * swing);
      pose.ankle[side] = -0.3 * g * std::sin(leg);
      if (params.carry_box) {
        pose.shoulder[side] = 0.6;
        pose.elbow[side] = 0.9;
      } else {
        pose.shoulder[side] = -g * 0.35 * std::sin(leg);  // arms swing against the legs
        pose.elbow[side] = 0.2 + g * 0.25 * (1 + std::sin(leg)) / 2;
        pose.shoulder_abduction[side] = 0.08;
      }
    }
    std::vector<SE3d> poses = ToVector(PersonPartPoses(look, pose));
    if (params.carry_box) {
      const double bob = pose.hip_height - 0.92;
      poses.push_back(pose.world_from_root * SE3d(SO3d(), Eigen::Vector3d(kCarriedBoxAhead * s, 0, (1.0 + bob) * s)));
    }
    return poses;
  };
  return actor;
}

Actor MakeSitter(const PersonLook& look, const SitterParams& params) {
  Actor actor;
  actor.kind = "sitter";
  actor.parts = PersonParts(look);
  actor.pose_at = [look, params](double t) {
    const double s = look.height / 1.75;
    PersonPose pose;
    pose.world_from_root = RootPose(params.seat.x(), params.seat.y(), params.heading);
    pose.hip_height = (params.seat_height + 0.07 * s) / s;
    pose.torso_pitch = 0.12 + 0.02 * std::sin(0.5 * t + params.phase);
    pose.torso_roll = 0.015 * std::sin(0.23 * t + 2 * params.phase);
    pose.head_yaw = 0.25 * std::sin(0.3 * t + params.phase);
    pose.head_pitch = 0.15 + 0.05 * std::sin(0.41 * t);
    std::array<double, 2> gesture{};
    for (std::size_t k = 0; k < params.gesture_times.size(); ++k) {
      const double x = (t - params.gesture_times[k]) / params.gesture_duration_s;
      if (x > 0 && x < 1) gesture[k % 2] = std::pow(std::sin(kPi * x), 2);
    }
    for (int side = 0; side < 2; ++side) {
      pose.hip[side] = 1.5;
      pose.knee[side] = 1.45;
      pose.shoulder[side] = 0.45 + 1.0 * gesture[static_cast<std::size_t>(side)];
      pose.elbow[side] = 1.0 + 0.5 * gesture[static_cast<std::size_t>(side)];
      pose.shoulder_abduction[side] = 0.12;
    }
    return ToVector(PersonPartPoses(look, pose));
  };
  return actor;
}

Actor MakeSlidingBox(const SlidingBoxParams& params) {
  Actor actor;
  actor.kind = "sliding box";
  ActorPart box{{}, kClassMovable};
  const Eigen::Vector3f half = (0.5 * params.size).cast<float>();
  const int m = params.material;
  AddBox(box.mesh, Eigen::Vector3f(-half.x(), -half.y(), 0), Eigen::Vector3f(half.x(), half.y(), 2 * half.z()),
         {m, m, m, m, m, m});
  actor.parts.push_back(std::move(box));
  actor.pose_at = [params](double t) {
    // rest, slide out, rest, slide back.
    const double period = 2 * (params.rest_s + params.slide_s);
    const double shifted = t + params.offset_s;
    const double tau = shifted - std::floor(shifted / period) * period;
    double f;
    if (tau < params.rest_s) {
      f = 0;
    } else if (tau < params.rest_s + params.slide_s) {
      f = SmoothStep((tau - params.rest_s) / params.slide_s);
    } else if (tau < 2 * params.rest_s + params.slide_s) {
      f = 1;
    } else {
      f = 1 - SmoothStep((tau - 2 * params.rest_s - params.slide_s) / params.slide_s);
    }
    return std::vector<SE3d>{SE3d(SO3d(), params.start + f * params.travel)};
  };
  return actor;
}

}  // namespace dlslam::synth
