#pragma once
// Where the camera is: the presets' hand-held-like motions (after the TUM
// fr3 sequences of the same names) and replays of real trajectories. Every
// path is expressed relative to its first pose and starts at the scene's
// viewpoint: world_from_cam(t) = viewpoint * first_from_cam(t).

#include <cstdint>
#include <optional>
#include <vector>

#include "dlslam/data/trajectory.h"
#include "dlslam/geometry/se3.h"
#include "dlslam/synth/preset.h"

namespace dlslam::synth {

// A preset's camera motion relative to the first pose (camera frame of the
// first pose: x right, y down, z forward). Smooth, with a seeded hand tremor.
class CameraMotion {
 public:
  CameraMotion(Preset preset, std::uint32_t seed);
  // first_from_cam at scene time t [s]; the identity plus tremor at t = 0.
  SE3d FirstFromCam(double t) const;

 private:
  Preset preset_;
  // Tremor: per degree of freedom three sinusoids (amplitude, frequency [Hz], phase).
  double tremor_[6][3][3] = {};
  double tremor_translation_m_ = 0.0;
  double tremor_rotation_rad_ = 0.0;
};

// The kidnap preset's timeline [s of scene time]: the camera pans for
// kKidnapMappingS, the lens is covered for kKidnapCoveredS (black frames, no
// depth; the camera is carried back meanwhile), then the motion replays from
// kKidnapResumeAtS on, i.e. the camera reappears at a pose it already had.
inline constexpr double kKidnapMappingS = 2.0;
inline constexpr double kKidnapCoveredS = 0.5;
inline constexpr double kKidnapResumeAtS = 0.4;
// True while the preset's lens is covered (only the kidnap preset has that).
bool LensCovered(Preset preset, double t);

// The loop preset: the camera goes round a horizontal circle (radius
// room::kLoopRadius around room::kLoopCentre, at the viewpoint's height and
// pitch) looking outward, turning right at a constant rate, one lap in
// kLoopLapS; by default it renders two laps and kLoopOverlapS more, so that
// the second lap sees the first lap's start again after the whole room.
inline constexpr double kLoopLapS = 18.0;
inline constexpr double kLoopOverlapS = 1.5;

// The frames a preset renders when the user asks for no number: two laps
// and the overlap for loop (1125 at 30 Hz), 300 for the others.
int PresetDefaultFrames(Preset preset, double fps);

// The camera path of a preset: `frames` poses at `fps` from `start_timestamp`
// (timestamps rounded to microseconds, as TUM files store them).
Trajectory PresetCameraPath(Preset preset, std::uint32_t seed, const SE3d& viewpoint, int frames, double fps,
                            double start_timestamp);

// The pose at time t: linear in translation, slerp in rotation between the
// two poses around t; nullopt outside [first, last] timestamp.
std::optional<SE3d> InterpolatePose(const Trajectory& trajectory, double t);

struct ReplayPath {
  Trajectory path;          // world_from_cam in the scene at the kept frame times
  int dropped_before = 0;   // frame times before the trajectory's first pose
  int dropped_after = 0;    // ... after its last pose
};

// Follows `trajectory` (world_from_cam in any world) at `frame_times`
// (increasing): poses interpolated at each time inside its span, expressed
// relative to the first kept one and placed at `viewpoint`. Empty
// frame_times: the trajectory's span sampled at `fps` from its first pose.
ReplayPath ReplayCameraPath(const Trajectory& trajectory, const std::vector<double>& frame_times,
                            const SE3d& viewpoint, double fps = 30.0);

}  // namespace dlslam::synth
