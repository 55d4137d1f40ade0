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

// Walked distance and speed fraction of a walk/stop cycle: ramp up, cruise,
// ramp down, stand. Integrals of the smooth step in closed form.
void WalkSchedule(const WalkerParams& p, double t, double& distance, double& fraction) {
  const double r = p.ramp_s, w = p.walk_s, period = 2 * r + w + p.stop_s;
  const double per_cycle = p.speed * (r + w);
  const double shifted = t + p.schedule_offset_s;
  const double cycles = std::floor(shifted / period);
  const double tau = shifted - cycles * period;
  auto ramp_integral = [](double x) { return x * x * x - 0.5 * x * x * x * x; };
  double d;
  if (tau < r) {
    const double x = tau / r;
    d = p.speed * r * ramp_integral(x);
    fraction = SmoothStep(x);
  } else if (tau < r + w) {
    d = p.speed * (0.5 * r + tau - r);
    fraction = 1.0;
  } else if (tau < 2 * r + w) {
    const double x = (tau - r - w) / r;
    d = p.speed * (0.5 * r + w + r * (x - ramp_integral(x)));
    fraction = 1.0 - SmoothStep(x);
  } else {
    d = per_cycle;
    fraction = 0.0;
  }
  distance = cycles * per_cycle + d;
}

// Arc length along an ellipse, tabulated, so walkers move at their real speed
// (the angle parameter alone would make them 5x faster at the long sides).
class EllipseArc {
 public:
  explicit EllipseArc(const Eigen::Vector2d& radii) : radii_(radii) {
    length_.resize(kSteps + 1);
    length_[0] = 0;
    for (int i = 1; i <= kSteps; ++i) length_[i] = length_[i - 1] + (Point(Angle(i)) - Point(Angle(i - 1))).norm();
  }
  double perimeter() const { return length_.back(); }
  // Arc length from angle 0 to `angle` in [0, 2 pi).
  double LengthAt(double angle) const {
    const double f = angle / (2 * kPi) * kSteps;
    const int i = std::clamp(static_cast<int>(f), 0, kSteps - 1);
    return length_[i] + (f - i) * (length_[i + 1] - length_[i]);
  }
  // The angle at arc length s (any real; wraps around).
  double AngleAt(double s) const {
    s -= std::floor(s / perimeter()) * perimeter();
    const auto it = std::upper_bound(length_.begin(), length_.end(), s);
    const int i = std::clamp(static_cast<int>(it - length_.begin()) - 1, 0, kSteps - 1);
    return Angle(i) + (s - length_[i]) / (length_[i + 1] - length_[i]) * (Angle(i + 1) - Angle(i));
  }

 private:
  static constexpr int kSteps = 2048;
  static double Angle(int i) { return 2 * kPi * i / kSteps; }
  Eigen::Vector2d Point(double a) const { return {radii_.x() * std::cos(a), radii_.y() * std::sin(a)}; }
  Eigen::Vector2d radii_;
  std::vector<double> length_;
};

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
  const auto arc = std::make_shared<const EllipseArc>(params.radii);
  const double start_angle = params.start_angle - std::floor(params.start_angle / (2 * kPi)) * 2 * kPi;
  const double start_s = arc->LengthAt(start_angle);
  actor.pose_at = [look, params, arc, start_s](double t) {
    double distance = 0, g = 0;
    WalkSchedule(params, t, distance, g);
    const double angle = arc->AngleAt(start_s + params.direction * distance);
    const double x = params.centre.x() + params.radii.x() * std::cos(angle);
    const double y = params.centre.y() + params.radii.y() * std::sin(angle);
    const double heading = std::atan2(params.direction * params.radii.y() * std::cos(angle),
                                      -params.direction * params.radii.x() * std::sin(angle));
    const double s = look.height / 1.75;
    const double phase = 2 * kPi * distance / (1.4 * s);  // one gait cycle = two steps
    PersonPose pose;
    pose.world_from_root = RootPose(x, y, heading);
    pose.hip_height = 0.92 - g * 0.012 * (1 - std::cos(2 * phase));
    pose.torso_pitch = 0.05 * g;
    pose.head_yaw = 0.12 * std::sin(0.35 * t + params.start_angle);
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
      poses.push_back(pose.world_from_root * SE3d(SO3d(), Eigen::Vector3d(0.36 * s, 0, (1.0 + bob) * s)));
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
