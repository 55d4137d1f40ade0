// dlslam synth: renders a synthetic dynamic RGB-D sequence with ground truth
// (poses, per-pixel class and motion masks) in the TUM layout.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <climits>
#include <filesystem>
#include <optional>
#include <string>

#include "cli_checks.h"
#include "commands.h"
#include "synth_run.h"
#include "dlslam/io/sequence_writer.h"
#include "dlslam/io/text_table.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/util/check.h"

namespace dlslam::app {

namespace {

// The first column of an associations (or rgb.txt) file: the frame times.
std::vector<double> ReadFrameTimes(const std::filesystem::path& path) {
  const io::TextTable table = io::ReadTextTable(path);
  std::vector<double> times;
  for (const io::TextRow& row : table.rows) {
    const double t = io::ParseDouble(row.fields.front(), path, row.line, "timestamp");
    if (!times.empty() && !(t > times.back())) {
      throw InputError(path, row.line, "timestamp {:.6f} is not after the previous one {:.6f}", t, times.back());
    }
    times.push_back(t);
  }
  if (times.empty()) throw InputError(path, 0, "holds no frame times");
  return times;
}

}  // namespace

void RunSynth(const SynthArgs& args, bool frames_given) {
  synth::SynthOptions options;
  options.preset = synth::ParsePreset(args.preset);
  options.seed = args.seed;
  options.frames = args.frames;
  options.scene.ceiling = !args.no_ceiling;
  options.render.motion_blur_samples = args.motion_blur;
  if (args.no_noise) {
    options.render.depth.enabled = false;
    options.render.colour_noise_sigma = 0;
  }
  std::optional<synth::ReplaySource> replay;
  std::string description = fmt::format("dlslam synth preset={} seed={}", args.preset, args.seed);
  if (!args.replay.empty()) {
    io::TrajectoryReadOptions read;
    read.min_poses = 2;
    replay = synth::ReplaySource{io::ReadTumTrajectory(args.replay, read), {}};
    if (!args.timestamps.empty()) replay->frame_times = ReadFrameTimes(args.timestamps);
    if (!frames_given) options.frames = INT_MAX;
    description += " replay=" + args.replay.filename().string();
  } else if (!args.timestamps.empty()) {
    throw Error("--timestamps needs --replay");
  } else if (!frames_given) {
    options.frames = synth::PresetDefaultFrames(options.preset, options.fps);
  }
  const synth::SynthSequence sequence(options, replay);
  if (replay) {
    const Trajectory& gt = replay->trajectory;
    if (sequence.dropped_before() + sequence.dropped_after() > 0) {
      spdlog::warn("{}: dropped {} frame time(s) before and {} after the trajectory's span [{:.6f}, {:.6f}]",
                   args.timestamps.string(), sequence.dropped_before(), sequence.dropped_after(),
                   gt.front().timestamp, gt.back().timestamp);
    }
    if (sequence.size() == 0) {
      throw InputError(args.timestamps, 0, "no frame time lies inside the trajectory's span [{:.6f}, {:.6f}] of {}",
                       gt.front().timestamp, gt.back().timestamp, args.replay.string());
    }
  }
  if (const int outside = sequence.frames_outside_free_space(); outside > 0) {
    spdlog::warn("the camera leaves the room's free space in {} of {} frames", outside, sequence.size());
  }
  io::SequenceWriterOptions write;
  write.fps = options.fps;
  write.description = description;
  write.force = args.force;
  io::SequenceWriter writer(args.out, options.camera, write);
  spdlog::info("rendering {} frames of '{}' (seed {}) into {}", sequence.size(), args.preset, args.seed,
               args.out.string());
  const auto start = std::chrono::steady_clock::now();
  double render_s = 0;
  for (int i = 0; i < sequence.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const synth::RenderedFrame frame = sequence.Render(i);
    render_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    writer.Add(sequence.camera_path()[static_cast<std::size_t>(i)].timestamp, frame.colour, frame.depth, frame.mask,
               frame.world_from_cam);
    if ((i + 1) % 100 == 0) spdlog::info("{} / {} frames", i + 1, sequence.size());
  }
  writer.Finish();
  const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("wrote {} frames in {:.1f} s ({:.1f} ms/frame rendering, {:.1f} ms/frame writing)", sequence.size(),
               total_s, 1e3 * render_s / sequence.size(), 1e3 * (total_s - render_s) / sequence.size());
}

void AddSynthCommand(CLI::App& app) {
  auto args = std::make_shared<SynthArgs>();
  CLI::App* cmd = app.add_subcommand("synth", "Render a synthetic dynamic RGB-D sequence with ground truth (TUM layout)");
  cmd->add_option("--preset", args->preset,
                  "static | walking_xyz | walking_rpy | walking_halfsphere | walking_static | sitting_static | kidnap "
                  "(pans 2 s, black 0.5 s, reappears at its pose of 0.4 s) | loop (no people; circles the room twice, "
                  "radius 1 m, looking outward at the walls, 18 s a lap, then 1.5 s of the first lap again)")
      ->capture_default_str();
  CLI::Option* frames = cmd->add_option("--frames", args->frames,
                                        "Number of frames (loop: default 1125 = two laps and 1.5 s; "
                                        "with --replay: at most, default all)")
                            ->capture_default_str()
                            ->check(WholeNumber(1, 100000000));
  cmd->add_option("--seed", args->seed, "Seed: the same seed gives byte-identical files")->capture_default_str()->check(WholeNumber(0, 4294967295));
  cmd->add_option("--out", args->out, "Output folder (created; refuses a non-empty folder it did not write)")
      ->required();
  cmd->add_flag("--force", args->force, "Write into a non-empty folder anyway (deletes nothing)");
  cmd->add_option("--replay", args->replay, "Follow this TUM trajectory (e.g. groundtruth.txt), relative to its first pose");
  cmd->add_option("--timestamps", args->timestamps,
                  "With --replay: frame times from the first column of this file (e.g. associations); default 30 Hz");
  cmd->add_flag("--no-noise", args->no_noise, "Perfect depth and colour (no sensor model)");
  cmd->add_flag("--no-ceiling", args->no_ceiling, "Leave the room open at the top");
  cmd->add_option("--motion-blur", args->motion_blur, "Instants averaged over the exposure (1 = off)")
      ->capture_default_str()
      ->check(WholeNumber(1, 16));
  cmd->callback([args, frames] { RunSynth(*args, frames->count() > 0); });
}

void RenderUnlessDone(const SynthArgs& args) {
  const std::filesystem::path& dir = args.out;
  const bool done = std::filesystem::exists(dir / io::SequenceWriter::kMarkerFile) &&
                    std::filesystem::exists(dir / "rgb.txt") &&
                    static_cast<int>(io::ReadTextTable(dir / "rgb.txt").rows.size()) == args.frames;
  if (done) {
    spdlog::info("reusing the rendered sequence {}", dir.string());
    return;
  }
  RunSynth(args, /*frames_given=*/true);
}

}  // namespace dlslam::app
