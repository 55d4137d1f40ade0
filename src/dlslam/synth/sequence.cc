#include "dlslam/synth/sequence.h"

#include "dlslam/synth/random.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {

namespace {
constexpr std::uint32_t kFrameStream = 3;
}  // namespace

void SynthOptions::Check() const {
  DLSLAM_CHECK_GT(frames, 0, "number of frames");
  DLSLAM_CHECK(fps > 0 && fps <= 1000, "frame rate {} Hz outside (0, 1000]", fps);
  DLSLAM_CHECK(start_timestamp >= 0 && start_timestamp < 1e10, "start timestamp {} outside [0, 1e10) s",
               start_timestamp);
  camera.Check();
  DLSLAM_CHECK(!camera.HasDistortion(), "camera '{}' has distortion; synth renders pinhole images", camera.name);
  scene.Check();
  render.Check();
}

SynthSequence::SynthSequence(const SynthOptions& options, const std::optional<ReplaySource>& replay)
    : options_(options) {
  options_.Check();
  scene_ = BuildScene(options_.preset, options_.seed, options_.scene);
  if (replay) {
    ReplayPath r = ReplayCameraPath(replay->trajectory, replay->frame_times, scene_.viewpoint, options_.fps);
    path_ = std::move(r.path);
    dropped_before_ = r.dropped_before;
    dropped_after_ = r.dropped_after;
    if (static_cast<int>(path_.size()) > options_.frames) path_.resize(static_cast<std::size_t>(options_.frames));
  } else {
    path_ = PresetCameraPath(options_.preset, options_.seed, scene_.viewpoint, options_.frames, options_.fps,
                             options_.start_timestamp);
  }
}

int SynthSequence::frames_outside_free_space() const {
  int outside = 0;
  for (const StampedPose& p : path_) outside += InFreeSpace(scene_, p.translation, 0.1) ? 0 : 1;
  return outside;
}

RenderedFrame SynthSequence::Render(int index) const {
  DLSLAM_CHECK(index >= 0 && index < size(), "frame {} outside [0, {})", index, size());
  std::mt19937 rng = MakeRng(options_.seed, kFrameStream, static_cast<std::uint32_t>(index));
  const auto i = static_cast<std::size_t>(index);
  CameraState state;
  state.world_from_cam = path_[i].world_from_cam();
  state.scene_time = path_[i].timestamp - path_.front().timestamp;
  SE3d previous;
  if (index > 0) {
    previous = path_[i - 1].world_from_cam();
    state.previous_world_from_cam = &previous;
    state.frame_interval_s = path_[i].timestamp - path_[i - 1].timestamp;
  }
  RenderedFrame frame = RenderFrame(scene_, options_.camera, state, options_.render, rng);
  if (LensCovered(options_.preset, state.scene_time)) {  // black, and no depth either
    frame.colour.setTo(cv::Scalar::all(0));
    frame.depth.setTo(0.f);
    frame.true_depth.setTo(0.f);
    frame.mask.setTo(0);
  }
  return frame;
}

}  // namespace dlslam::synth
