#include "dlslam/synth/camera_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dlslam/synth/random.h"
#include "dlslam/synth/room.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {

constexpr std::uint32_t kCameraStream = 2;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// One axis at a time: in window w (of `window` seconds, cycling through
// `count` windows) the value swings sinusoidally with `period`, under a
// half-sine envelope so that position and velocity are continuous.
double AxisSweep(double t, int axis, int count, double window, double period, double amplitude) {
  const double cycle = window * count;
  const double tau = t - std::floor(t / cycle) * cycle - axis * window;
  if (tau < 0 || tau >= window) return 0.0;
  return amplitude * std::sin(2 * kPi * tau / period) * std::sin(kPi * tau / window);
}

SE3d LookAt(const Eigen::Vector3d& position, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - position).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z).normalized();  // first frame's down x forward
  Eigen::Matrix3d R;
  R << x, z.cross(x), z;
  return SE3d(SO3d(R), position);
}

// The kidnap preset's pan at pan time u: 0.3 m to the right and 15 deg of
// yaw over the mapping stretch, with smooth start and end.
void KidnapPan(double u, Eigen::Vector3d& p, Eigen::Vector3d& rpy) {
  const double s = 0.5 * (1 - std::cos(kPi * std::clamp(u / kKidnapMappingS, 0.0, 1.0)));
  p = Eigen::Vector3d(0.3 * s, 0.0, 0.05 * s);
  rpy = Eigen::Vector3d(0.0, 15 * kDeg * s, 0.0);
}

// The loop preset's first_from_cam at time t. In the level frame (the first
// camera's frame without its pitch: x right, y down along gravity, z forward
// horizontally) the circle's centre is the radius behind the start and the
// camera turns about the vertical; the pitch stays that of the viewpoint.
SE3d LoopFirstFromCam(double t) {
  const double yaw = 2 * kPi * t / kLoopLapS;
  const double r = room::kLoopRadius;
  const SO3d level_from_first = SO3d::Exp(Eigen::Vector3d(-room::kViewpointPitchDown, 0, 0));
  const SE3d level_from_cam(SO3d::Exp(Eigen::Vector3d(0, yaw, 0)) * level_from_first,
                            Eigen::Vector3d(r * std::sin(yaw), 0, r * (std::cos(yaw) - 1)));
  return SE3d(level_from_first.Inverse(), Eigen::Vector3d::Zero()) * level_from_cam;
}

}  // namespace

int PresetDefaultFrames(Preset preset, double fps) {
  DLSLAM_CHECK_GT(fps, 0.0, "frame rate [Hz]");
  if (preset == Preset::kLoop) return static_cast<int>(std::lround((2 * kLoopLapS + kLoopOverlapS) * fps));
  return 300;
}

bool LensCovered(Preset preset, double t) {
  return preset == Preset::kKidnap && t >= kKidnapMappingS && t < kKidnapMappingS + kKidnapCoveredS;
}

CameraMotion::CameraMotion(Preset preset, std::uint32_t seed) : preset_(preset) {
  std::mt19937 rng = MakeRng(seed, kCameraStream);
  for (auto& dof : tremor_) {
    for (auto& wave : dof) {
      wave[0] = Uniform(rng, 0.5, 1.0);         // relative amplitude
      wave[1] = LogUniform(rng, 0.15, 2.0);     // frequency [Hz]
      wave[2] = Uniform(rng, 0.0, 2 * kPi);     // phase
    }
  }
  const bool still = preset == Preset::kWalkingStatic || preset == Preset::kSittingStatic;
  tremor_translation_m_ = still ? 0.002 : 0.006;
  tremor_rotation_rad_ = (still ? 0.15 : 0.6) * kDeg;
}

SE3d CameraMotion::FirstFromCam(double t) const {
  Eigen::Matrix<double, 6, 1> tremor;
  for (int d = 0; d < 6; ++d) {
    double v = 0;
    for (const auto& w : tremor_[d]) v += w[0] * (std::sin(2 * kPi * w[1] * t + w[2]) - std::sin(w[2]));
    tremor[d] = v * (d < 3 ? tremor_translation_m_ : tremor_rotation_rad_) / 2.0;
  }
  const SE3d shake(SO3d::Exp(tremor.tail<3>()), tremor.head<3>());
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();  // rotation vector in the camera frame
  switch (preset_) {
    case Preset::kStatic:  // slow sweeps, like the static fr3 structure/texture sequences
      for (int a = 0; a < 3; ++a) p[a] = AxisSweep(t, a, 3, 16.0, 8.0, 0.25);
      break;
    case Preset::kWalkingXyz:
      p.x() = AxisSweep(t, 0, 4, 12.0, 6.0, 0.4);
      p.y() = AxisSweep(t, 1, 4, 12.0, 6.0, 0.3);
      p.z() = AxisSweep(t, 2, 4, 12.0, 6.0, 0.4);
      for (int a = 0; a < 3; ++a) p[a] += AxisSweep(t, 3, 4, 12.0, 6.0 + a, 0.25);  // all axes at once
      rpy = Eigen::Vector3d(3 * std::sin(0.31 * t), 4 * (std::sin(0.23 * t + 1) - std::sin(1.0)), 2 * std::sin(0.17 * t)) * kDeg;
      break;
    case Preset::kWalkingRpy:
      rpy.x() = AxisSweep(t, 1, 3, 12.0, 6.0, 20 * kDeg);  // pitch
      rpy.y() = AxisSweep(t, 2, 3, 12.0, 6.0, 30 * kDeg);  // yaw
      rpy.z() = AxisSweep(t, 0, 3, 12.0, 6.0, 25 * kDeg);  // roll
      p = Eigen::Vector3d(0.03 * std::sin(0.4 * t), 0.02 * (std::sin(0.3 * t + 2) - std::sin(2.0)), 0.03 * std::sin(0.2 * t));
      break;
    case Preset::kWalkingHalfsphere: {
      // On a sphere of radius 0.5 m around a point 0.5 m ahead, on its near
      // half, looking at the scene 2.5 m ahead.
      const double r = 0.5;
      const double theta = 1.3 * 0.5 * (1 - std::cos(2 * kPi * t / 20.0));  // up to 75 deg
      const double phi = 2 * kPi * t / 13.0;
      const Eigen::Vector3d position(r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                                     r - r * std::cos(theta));
      return LookAt(position, Eigen::Vector3d(0, 0, 2.5)) * shake;
    }
    case Preset::kKidnap: {
      const double resume = kKidnapMappingS + kKidnapCoveredS;
      double u = t;  // pan time
      if (t >= resume) {
        u = kKidnapResumeAtS + (t - resume);
      } else if (t >= kKidnapMappingS) {  // covered: carried back from the end to the resume pose
        u = kKidnapMappingS + (kKidnapResumeAtS - kKidnapMappingS) * (t - kKidnapMappingS) / kKidnapCoveredS;
      }
      KidnapPan(u, p, rpy);
      break;
    }
    case Preset::kLoop: return LoopFirstFromCam(t) * shake;
    case Preset::kWalkingStatic:
    case Preset::kSittingStatic: break;
  }
  return SE3d(SO3d::Exp(rpy), p) * shake;
}

Trajectory PresetCameraPath(Preset preset, std::uint32_t seed, const SE3d& viewpoint, int frames, double fps,
                            double start_timestamp) {
  DLSLAM_CHECK_GT(frames, 0, "frames");
  DLSLAM_CHECK_GT(fps, 0.0, "frame rate [Hz]");
  const CameraMotion motion(preset, seed);
  Trajectory path;
  path.reserve(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) {
    const double t = std::round((start_timestamp + i / fps) * 1e6) / 1e6;
    path.emplace_back(t, viewpoint * motion.FirstFromCam(t - start_timestamp));
  }
  return path;
}

std::optional<SE3d> InterpolatePose(const Trajectory& trajectory, double t) {
  if (trajectory.empty() || t < trajectory.front().timestamp || t > trajectory.back().timestamp) return std::nullopt;
  const auto after = std::upper_bound(trajectory.begin(), trajectory.end(), t,
                                      [](double time, const StampedPose& p) { return time < p.timestamp; });
  if (after == trajectory.end()) return trajectory.back().world_from_cam();
  const StampedPose& b = *after;
  const StampedPose& a = *(after - 1);
  const double f = (t - a.timestamp) / (b.timestamp - a.timestamp);
  const Eigen::Quaterniond qa = a.rotation.normalized(), qb = b.rotation.normalized();
  return SE3d(qa.slerp(f, qb), a.translation + f * (b.translation - a.translation));
}

ReplayPath ReplayCameraPath(const Trajectory& trajectory, const std::vector<double>& frame_times,
                            const SE3d& viewpoint, double fps) {
  DLSLAM_CHECK(!trajectory.empty(), "replay needs a trajectory");
  DLSLAM_CHECK_GT(fps, 0.0, "frame rate [Hz]");
  std::vector<double> times = frame_times;
  if (times.empty()) {
    const double t0 = trajectory.front().timestamp;
    for (int i = 0; t0 + i / fps <= trajectory.back().timestamp; ++i) {
      times.push_back(std::round((t0 + i / fps) * 1e6) / 1e6);
    }
  }
  ReplayPath out;
  std::optional<SE3d> first_from_world;
  for (double t : times) {
    if (t < trajectory.front().timestamp) {
      ++out.dropped_before;
      continue;
    }
    const std::optional<SE3d> pose = InterpolatePose(trajectory, t);
    if (!pose) {
      ++out.dropped_after;
      continue;
    }
    if (!first_from_world) first_from_world = pose->Inverse();
    out.path.emplace_back(t, viewpoint * (*first_from_world * *pose));
  }
  return out;
}

}  // namespace dlslam::synth
