#pragma once
// Rendering a synthetic sequence to a folder: `dlslam synth` and the demo.

#include <cstdint>
#include <filesystem>
#include <string>

namespace dlslam::app {

struct SynthArgs {
  std::string preset = "walking_xyz";
  int frames = 300;
  std::uint32_t seed = 1;
  std::filesystem::path out;
  bool force = false;
  std::filesystem::path replay;
  std::filesystem::path timestamps;
  bool no_noise = false;
  bool no_ceiling = false;
  int motion_blur = 1;
};

// Renders and writes the sequence; `frames_given`: --frames was on the
// command line (a replay otherwise takes every frame time).
void RunSynth(const SynthArgs& args, bool frames_given);

// Renders `args.out` unless a folder we rendered before with the same number
// of frames is there (then logs that it is reused).
void RenderUnlessDone(const SynthArgs& args);

}  // namespace dlslam::app
