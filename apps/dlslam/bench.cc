// dlslam bench: how fast the whole system runs on this machine, stage by
// stage, in each mode, on one sequence (a folder, or a synthetic preset
// rendered once). Prints the stages against the camera's frame budget and
// the real-time factor, and writes everything to <out>/bench.json. The
// Google Benchmark binaries (dlslam_bench_*) time single components; this
// times them together, threads and all, as `dlslam run` runs them.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_checks.h"
#include "dlslam/config/config_file.h"
#include "dlslam/data/camera.h"
#include "commands.h"
#include "dlslam/io/file_util.h"
#include "dlslam/io/sequence.h"
#include "dlslam/util/check.h"
#include "dlslam/util/timing.h"
#include "run_sequence.h"
#include "synth_run.h"

namespace dlslam::app {

namespace {

namespace fs = std::filesystem;

struct BenchArgs {
  fs::path sequence;                  // a TUM-layout folder; empty = render --preset
  std::string preset = "walking_xyz";
  int frames = 300;                   // of the preset; a folder is run whole unless --max-frames
  std::size_t max_frames = 0;
  std::string modes = "orb,geometry,full";
  bool sequential = false;
  int segment_every = 1;              // modes semantic, full: segment every k-th frame
  bool async_masks = false;           // modes semantic, full: never wait for the network
  double realtime_rate = 0.0;         // --realtime[=RATE]: frames arrive as from a live camera; 0 = as fast as possible
  fs::path semantic_model;            // "" = the shipped network
  fs::path config;                    // every option from one YAML file; bench's flags override it
  std::set<std::string> given;        // the flags given on the command line
  double camera_hz = 30.0;            // the frame budget is 1000 / camera_hz ms
  fs::path out = "dlslam-bench";
  io::RgbdSequenceOptions sequence_options;
};

struct ModeRun {
  std::string mode;
  RunOutcome outcome;
  double wall_s = 0.0;
  double sequence_s = 0.0;  // time span of the frames run
};

std::vector<std::string> ParseModes(const std::string& list) {
  std::vector<std::string> modes;
  std::stringstream in(list);
  for (std::string mode; std::getline(in, mode, ',');) {
    if (mode.empty()) continue;
    if (mode != "orb" && mode != "semantic" && mode != "geometry" && mode != "full") {
      throw Error(fmt::format("--modes: unknown mode '{}' (valid: orb, semantic, geometry, full)", mode));
    }
    if (std::find(modes.begin(), modes.end(), mode) == modes.end()) modes.push_back(mode);
  }
  if (modes.empty()) throw Error(fmt::format("--modes: no mode in '{}'", list));
  return modes;
}

// The 1-minute load average, when the system tells it: timings on a shared
// machine mean little without it.
std::optional<double> LoadAverage() {
  std::ifstream in("/proc/loadavg");
  double load = 0.0;
  if (in >> load) return load;
  return std::nullopt;
}

// Stages in the order a frame meets them, then the background threads';
// stages not listed here follow in name order.
std::vector<std::string> StageOrder(const std::vector<ModeRun>& runs) {
  static const std::vector<std::string> kKnown = {
      "orb_extraction", "semantic", "semantic_wait", "geometry", "tracking", "frame_total",
      "keyframe_handover", "keyframe_bow", "local_mapping", "triangulation", "fusion", "local_bundle_adjustment",
      "loop_detection", "loop_wait_for_mapping", "loop_correction", "global_bundle_adjustment"};
  std::vector<std::string> order;
  for (const std::string& stage : kKnown) {
    for (const ModeRun& r : runs) {
      if (r.outcome.stats.timing_ms.count(stage)) {
        order.push_back(stage);
        break;
      }
    }
  }
  for (const ModeRun& r : runs) {
    for (const auto& [stage, summary] : r.outcome.stats.timing_ms) {
      if (std::find(order.begin(), order.end(), stage) == order.end()) order.push_back(stage);
    }
  }
  return order;
}

std::string Table(const std::vector<ModeRun>& runs, double budget_ms) {
  const auto row = [&](const std::string& label, auto&& cell) {
    std::string line = fmt::format("{:<26}", label);
    for (const ModeRun& r : runs) line += fmt::format(" {:>19}", cell(r));
    return line + "\n";
  };
  std::string table = "\n" + row("", [](const ModeRun& r) { return r.mode; });
  table += row("stage [ms]", [](const ModeRun&) { return std::string("median / p95"); });
  for (const std::string& stage : StageOrder(runs)) {
    table += row(stage, [&](const ModeRun& r) {
      const auto it = r.outcome.stats.timing_ms.find(stage);
      if (it == r.outcome.stats.timing_ms.end()) return std::string("-");
      return fmt::format("{:.1f} / {:.1f}", it->second.median, it->second.p95);
    });
  }
  table += row(fmt::format("frames over {:.1f} ms", budget_ms), [&](const ModeRun& r) {
    const auto it = r.outcome.stats.timing_ms.find("frame_total");
    if (it == r.outcome.stats.timing_ms.end()) return std::string("-");
    // The median and p95 bound the share: say which side of them it lies.
    const TimingSummary& t = it->second;
    if (t.max <= budget_ms) return std::string("none");
    if (t.p95 <= budget_ms) return std::string("< 5 %");
    if (t.median <= budget_ms) return std::string("5-50 %");
    return std::string("> 50 %");
  });
  table += row("frames tracked", [](const ModeRun& r) {
    return fmt::format("{}/{}", r.outcome.stats.frames_tracked, r.outcome.stats.frames);
  });
  table += row("frames coasted", [](const ModeRun& r) { return fmt::format("{}", r.outcome.stats.frames_coasted); });
  table += row("of tracked: in a new map", [](const ModeRun& r) {
    return fmt::format("{}", r.outcome.stats.frames_new_map);
  });
  table += row("frames without a pose", [](const ModeRun& r) {
    return fmt::format("{}", r.outcome.stats.frames_without_pose());
  });
  if (std::any_of(runs.begin(), runs.end(), [](const ModeRun& r) { return r.outcome.stats.frames_dropped > 0; })) {
    table += row("of those: dropped (live)", [](const ModeRun& r) {
      return fmt::format("{}", r.outcome.stats.frames_dropped);
    });
  }
  table += row("wall time [s]", [](const ModeRun& r) { return fmt::format("{:.1f}", r.wall_s); });
  table += row("real-time factor", [](const ModeRun& r) {
    return r.wall_s > 0 && r.sequence_s > 0 ? fmt::format("{:.2f}x", r.sequence_s / r.wall_s) : std::string("-");
  });
  table += row("ATE RMSE [m]", [](const ModeRun& r) {
    return r.outcome.evaluation ? fmt::format("{:.4f}", r.outcome.evaluation->ate.error.rmse) : std::string("-");
  });
  const auto camera_ate = [](const ModeRun& r) -> std::optional<double> {
    if (!r.outcome.evaluation || !r.outcome.evaluation->bonn_camera) return std::nullopt;
    return r.outcome.evaluation->bonn_camera->ate.error.rmse;
  };
  if (!runs.empty() && camera_ate(runs.front())) {  // a Bonn sequence: its marker poses as published, above
    table += row("ATE RMSE [m], Bonn camera poses", [&](const ModeRun& r) {
      const std::optional<double> ate = camera_ate(r);
      return ate ? fmt::format("{:.4f}", *ate) : std::string("-");
    });
  }
  return table;
}

nlohmann::ordered_json Json(const BenchArgs& args, const fs::path& sequence, const std::vector<ModeRun>& runs,
                            double budget_ms, std::optional<double> load_before) {
  nlohmann::ordered_json j;
  j["sequence"] = sequence.string();
  j["threads"] = args.sequential ? "sequential" : "threaded";
  j["segment_every"] = args.segment_every;
  j["async_masks"] = args.async_masks;
  j["realtime_rate"] = args.realtime_rate;
  j["config"] = args.config.string();  // "" = the defaults; its values under the flags given
  j["budget_ms"] = budget_ms;
  j["cores"] = std::thread::hardware_concurrency();
  j["load_average_before"] = load_before ? nlohmann::ordered_json(*load_before) : nlohmann::ordered_json();
  const std::optional<double> load_after = LoadAverage();
  j["load_average_after"] = load_after ? nlohmann::ordered_json(*load_after) : nlohmann::ordered_json();
  for (const ModeRun& r : runs) {
    nlohmann::ordered_json m;
    m["mode"] = r.mode;
    m["frames"] = r.outcome.stats.frames;
    m["frames_tracked"] = r.outcome.stats.frames_tracked;
    m["frames_coasted"] = r.outcome.stats.frames_coasted;
    m["frames_new_map"] = r.outcome.stats.frames_new_map;
    m["frames_without_pose"] = r.outcome.stats.frames_without_pose();
    m["frames_dropped"] = r.outcome.stats.frames_dropped;
    m["maps_started"] = r.outcome.stats.maps_started;
    m["maps_merged"] = r.outcome.stats.maps_merged;
    m["wall_s"] = r.wall_s;
    m["sequence_s"] = r.sequence_s;
    m["realtime_factor"] = r.wall_s > 0 ? r.sequence_s / r.wall_s : 0.0;
    m["ate_rmse"] = r.outcome.evaluation ? nlohmann::ordered_json(r.outcome.evaluation->ate.error.rmse)
                                         : nlohmann::ordered_json();
    if (r.outcome.evaluation && r.outcome.evaluation->bonn_camera) {
      m["ate_rmse_bonn_camera"] = r.outcome.evaluation->bonn_camera->ate.error.rmse;
    }
    for (const auto& [stage, t] : r.outcome.stats.timing_ms) {
      m["stages_ms"][stage] = {{"count", t.count}, {"median", t.median}, {"p95", t.p95}, {"max", t.max}};
    }
    j["runs"].push_back(m);
  }
  return j;
}

void RunBench(const BenchArgs& args) {
  DLSLAM_CHECK(args.camera_hz > 0, "--camera-hz must be positive, got {}", args.camera_hz);
  const std::vector<std::string> modes = ParseModes(args.modes);
  // A bad file fails here, before a preset is rendered (each run reads it again).
  if (!args.config.empty()) {
    config::RunOptions checked;
    config::LoadConfig(args.config, &checked);
  }
  fs::create_directories(args.out);
  fs::path sequence = args.sequence;
  if (sequence.empty()) {
    SynthArgs synth;
    synth.preset = args.preset;
    synth.frames = args.frames;
    synth.out = args.out / args.preset;
    RenderUnlessDone(synth);
    sequence = synth.out;
  }
  const io::RgbdSequence frames = io::RgbdSequence::Open(sequence, args.sequence_options);
  DLSLAM_CHECK(frames.size() > 0, "{}: no frames", sequence.string());
  const std::size_t n = args.max_frames > 0 ? std::min(args.max_frames, frames.size()) : frames.size();
  const double sequence_s = frames.frames()[n - 1].timestamp() - frames.frames()[0].timestamp();

  const std::optional<double> load_before = LoadAverage();
  std::vector<ModeRun> runs;
  for (const std::string& mode : modes) {
    RunArgs run;
    run.sequence = sequence;
    run.sequence_options = args.sequence_options;
    run.mode = mode;
    run.sequential = args.sequential;
    run.segment_every = args.segment_every;
    run.async_masks = args.async_masks;
    run.realtime_rate = args.realtime_rate;
    run.semantic_model = args.semantic_model;
    run.config = args.config;
    run.given = args.given;
    run.given.insert("--mode");  // each run's mode is bench's, whatever the file says
    run.max_frames = args.max_frames;
    run.out = args.out / (mode + "_trajectory.txt");
    run.report = args.out / (mode + "_report.json");
    spdlog::info("bench: mode {} on {}", mode, sequence.string());
    Stopwatch watch;
    RunOutcome outcome = RunSequence(run);
    runs.push_back({mode, std::move(outcome), watch.ElapsedMs() / 1e3, sequence_s});
  }

  const double budget_ms = 1000.0 / args.camera_hz;
  spdlog::info("bench: {} frames of {} ({:.1f} s at the camera's rate), {}, {} cores, load average {}{}", n,
               sequence.string(), sequence_s, args.sequential ? "sequential" : "threaded",
               std::thread::hardware_concurrency(),
               load_before ? fmt::format("{:.2f}", *load_before) : std::string("unknown"),
               Table(runs, budget_ms));
  const fs::path json = args.out / "bench.json";
  const std::string text = Json(args, sequence, runs, budget_ms, load_before).dump(2) + "\n";
  io::WriteFileAtomically(json, [&](std::ostream& out) { out << text; });
  spdlog::info("wrote {} (per-mode reports and trajectories beside it)", json.string());
}

}  // namespace

void AddBenchCommand(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Time the whole system stage by stage in each mode, against the camera's frame budget");
  cmd->add_option("--sequence", args->sequence, "RGB-D sequence folder (TUM layout); default: render --preset");
  cmd->add_option("--preset", args->preset, "Synthetic preset to render when no --sequence is given")
      ->capture_default_str();
  cmd->add_option("--frames", args->frames, "Frames of the preset")->capture_default_str()->check(WholeNumber(30, 100000));
  cmd->add_option("--max-frames", args->max_frames, "Stop each run after this many frames (0 = all)")->check(WholeNumber(0, 1000000000));
  cmd->add_option("--modes", args->modes, "Comma-separated modes: orb, semantic, geometry, full")->capture_default_str();
  cmd->add_flag("--sequential", args->sequential, "Run local mapping inline (default: threaded, as deployed)");
  cmd->add_option("--segment-every", args->segment_every,
                  "Modes semantic, full: segment every k-th frame, propagating the mask to the frames between")
      ->capture_default_str()
      ->check(WholeNumber(1, 100));
  cmd->add_flag("--async-masks", args->async_masks,
               "Modes semantic, full: never wait for the network; use its newest masks, carried to each frame");
  cmd->add_flag("--realtime{1}", args->realtime_rate,
                "Play the frames as a live camera delivers them (--realtime=RATE: at RATE x its speed): stage "
                "'latency' (arrival to pose) and frames dropped for want of time")
      ->check(RealNumber(0.01, 100));
  cmd->add_option("--semantic-model", args->semantic_model, "Segmentation network (ONNX); default: the shipped one");
  cmd->add_option("--config", args->config,
                  "Every option of every module from one YAML file (dlslam config dump); flags given here override it");
  cmd->add_option("--camera-hz", args->camera_hz, "Camera frame rate: the budget per frame is 1000 / Hz ms")
      ->capture_default_str()->check(RealNumber(0.1, 1000));
  cmd->add_option("--out", args->out, "Output folder: bench.json, per-mode reports and trajectories")
      ->capture_default_str();
  cmd->add_option("--camera", args->sequence_options.camera_preset, "Camera preset: fr1, fr2, fr3, bonn");
  cmd->add_option("--depth-factor", args->sequence_options.depth_factor, "Raw depth units per metre")->check(RealNumber(kMinDepthFactor, kMaxDepthFactor));
  cmd->callback([args, cmd] {
    args->given = GivenFlags(*cmd);
    RunBench(*args);
  });
}

}  // namespace dlslam::app
