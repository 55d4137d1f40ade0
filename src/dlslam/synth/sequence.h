#pragma once
// A synthetic RGB-D sequence: a scene, a camera path and the renderer. Any
// frame can be rendered on its own, and the same seed and index always give
// the same frame.

#include <cstdint>
#include <optional>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/data/trajectory.h"
#include "dlslam/synth/camera_path.h"
#include "dlslam/synth/preset.h"
#include "dlslam/synth/renderer.h"
#include "dlslam/synth/scene.h"

namespace dlslam::synth {

struct SynthOptions {
  Preset preset = Preset::kWalkingXyz;      // scene content and camera motion
  int frames = 300;                         // frames to render (a replay: at most this many)
  std::uint32_t seed = 1;                   // everything random derives from it
  double fps = 30.0;                        // frame rate of synthetic paths [Hz]
  double start_timestamp = 1700000000.0;    // first frame's time of synthetic paths [s, Unix epoch]
  CameraIntrinsics camera = CameraPreset("freiburg3");  // pinhole, no distortion
  SceneOptions scene;
  RenderOptions render;

  // Throws dlslam::Error naming the offending value.
  void Check() const;
};

// A real trajectory for the camera to follow (see ReplayCameraPath).
struct ReplaySource {
  Trajectory trajectory;           // world_from_cam, e.g. a TUM groundtruth.txt
  std::vector<double> frame_times; // [s], increasing; empty: 30 Hz over the trajectory
};

class SynthSequence {
 public:
  explicit SynthSequence(const SynthOptions& options, const std::optional<ReplaySource>& replay = std::nullopt);

  int size() const { return static_cast<int>(path_.size()); }
  const Trajectory& camera_path() const { return path_; }  // world_from_cam per frame
  const Scene& scene() const { return scene_; }
  const SynthOptions& options() const { return options_; }
  // Replay only: frame times outside the trajectory that were dropped.
  int dropped_before() const { return dropped_before_; }
  int dropped_after() const { return dropped_after_; }
  // Frames whose camera is not in the room's free space (0.1 m margin).
  int frames_outside_free_space() const;

  // Deterministic in (seed, index); throws dlslam::Error for a bad index.
  RenderedFrame Render(int index) const;

 private:
  SynthOptions options_;
  Scene scene_;
  Trajectory path_;
  int dropped_before_ = 0;
  int dropped_after_ = 0;
};

}  // namespace dlslam::synth
