// dlslam run: SLAM on a sequence folder, writing the camera trajectory and a
// JSON report; evaluates against the folder's ground truth when it has one.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>
#include <fstream>
#include <memory>

#include "cli_checks.h"
#include "dlslam/data/camera.h"
#include "commands.h"
#include "dlslam/config/config_file.h"
#include "dense_output.h"
#include "frame_view_image.h"
#include "html_report.h"
#include "live_view.h"
#include "dlslam/io/file_util.h"
#include "dlslam/io/frame_prefetcher.h"
#include "dlslam/io/live_playback.h"
#include "dlslam/io/sequence.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/actors.h"
#include "dlslam/util/check.h"
#include "run_report.h"
#include "run_sequence.h"
#include "semantic_prior.h"

namespace dlslam::app {

namespace {

// --fusion takes "geometry-confirms" as well as the library's "geometry_confirms".
dynamic::FusionPolicy ParseFusion(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return dynamic::ParseFusionPolicy(name);
}

void LogDynamicSummary(const RunStats& stats) {
  const DynamicStats& d = stats.dynamic;
  if (d.mode != DynamicMode::kOrb) {
    spdlog::info("dynamic (mode {}, search {}): {} points tested, {} dynamic, {} keypoints removed, {:.1f} % of the image "
                 "removed, {} map points culled, {} moving movable-class segments dropped",
                 ToString(d.mode), dynamic::ToString(d.search), d.keypoints_tested, d.keypoints_dynamic,
                 d.keypoints_removed, 100.0 * d.image_share_removed().value_or(0.0), d.map_points_culled, d.movable_segments_dropped);
  }
  if (d.mode != DynamicMode::kOrb && d.frames_with_truth > 0) {
    const auto show = [](const std::optional<double>& v) { return v ? fmt::format("{:.3f}", *v) : "-"; };
    spdlog::info("removed keypoints vs ground truth ({} frames): precision {}, recall {}", d.frames_with_truth,
                 show(d.precision()), show(d.recall()));
  }
}

}  // namespace

std::filesystem::path PoseSourcesPath(const std::filesystem::path& trajectory) {
  std::filesystem::path out = trajectory;
  out.replace_extension(".sources.txt");
  return out;
}

void WritePoseSources(const std::filesystem::path& path, const std::vector<FramePoseSource>& sources) {
  io::WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# how each frame's pose was obtained: tracked, relocalized, coasted (motion model, not confirmed by the "
           "map), new_map (tracked in a map started after a loss, before it merged into the older one) or none\n"
           "# timestamp source\n";
    for (const FramePoseSource& s : sources) out << fmt::format("{:.6f} {}\n", s.timestamp, ToString(s.source));
  });
}

// The ground-truth pose within 20 ms of `t`, if any.
std::optional<SE3d> PoseNear(const Trajectory& truth, double t) {
  const auto it = std::lower_bound(truth.begin(), truth.end(), t,
                                   [](const StampedPose& p, double time) { return p.timestamp < time; });
  const StampedPose* best = nullptr;
  for (auto c = it == truth.begin() ? it : std::prev(it); c != truth.end() && c <= it; ++c) {
    if (!best || std::abs(c->timestamp - t) < std::abs(best->timestamp - t)) best = &*c;
  }
  if (!best || std::abs(best->timestamp - t) > 0.02) return std::nullopt;
  return best->world_from_cam();
}

// The run's options: the defaults, then --config FILE, then the flags given
// on the command line (without --config every flag counts, with its
// default, as it always has).
config::RunOptions RunOptionsFrom(const RunArgs& args) {
  config::RunOptions run;
  if (!args.config.empty()) config::LoadConfig(args.config, &run);
  const auto flag = [&args](const char* name) { return args.config.empty() || args.given.count(name) > 0; };
  SystemOptions& options = run.system;
  if (flag("--sequential")) options.sequential = args.sequential;
  if (flag("--no-relocalization")) options.relocalization = !args.no_relocalization;
  if (flag("--no-loop")) options.loop_closing = !args.no_loop;
  if (flag("--no-movables")) options.dynamic.fusion.drop_moving_movables = !args.no_movables;
  if (flag("--vocabulary")) options.vocabulary = args.vocabulary;
  if (flag("--bundle-solver")) options.mapping.bundle.solver = ParseBundleSolver(args.bundle_solver);
  if (flag("--mode")) options.dynamic.mode = ParseDynamicMode(args.mode);
  if (flag("--geometry-search")) options.dynamic.geometry.search = dynamic::ParseSearchKind(args.geometry_search);
  if (flag("--fusion")) options.dynamic.fusion.policy = ParseFusion(args.fusion);
  if (flag("--semantic-model")) options.semantic.segmenter.model_path = args.semantic_model;
  if (flag("--segment-every")) options.semantic.worker.segment_every = args.segment_every;
  if (flag("--async-masks")) options.semantic.wait_for_masks = !args.async_masks;
  if (!args.dense_map.empty()) options.keep_keyframe_images = true;
  if (args.localize) options.localization_only = true;
  if (flag("--dense-voxel")) {
    run.dense.voxel_size = args.dense_voxel;
    run.dense.truncation = 4 * args.dense_voxel;
  }
  // The network unless masks are given (or the file turned it off).
  if (!args.semantic_masks.empty()) options.semantic.network = false;
  run.Check();
  return run;
}

RunOutcome RunSequence(const RunArgs& args) {
  if (args.localize && args.load_map.empty()) throw Error("--localize needs a map to localize in: --load-map FILE");
  config::RunOptions run_options = RunOptionsFrom(args);
  // Before anything is loaded: a bad output folder fails at once.
  std::optional<RemovalImageWriter> removal_images;
  if (!args.removal_images.empty()) removal_images.emplace(args.removal_images, args.removal_images_every);
  SystemOptions& options = run_options.system;
  const bool wants_prior = UsesSemanticPrior(options.dynamic.mode);
  io::RgbdSequenceOptions sequence_options = args.sequence_options;
  // A config file with ORB-SLAM3 camera keys is the camera's settings file too.
  if (!args.config.empty() && sequence_options.settings_file.empty() && config::HasCameraKeys(args.config)) {
    sequence_options.settings_file = args.config;
  }
  const io::RgbdSequence sequence = io::RgbdSequence::Open(args.sequence, sequence_options);
  const CameraIntrinsics& camera = sequence.camera();
  // The network runs in the library's semantic thread; masks given by the
  // user come through a prior source instead.
  std::unique_ptr<SemanticPriorSource> prior_source;
  options.semantic.network = options.semantic.network && wants_prior;
  const dense::TsdfOptions& dense_options = run_options.dense;
  std::map<double, cv::Mat> keyframe_people;  // ground-truth people of keyframes, for the dense map's statistics
  if (options.semantic.network) {
    const int every = options.semantic.worker.segment_every;
    spdlog::info("semantic prior: the segmentation network, {}",
                 !options.semantic.wait_for_masks ? std::string("asynchronous (newest masks carried to each frame)")
                 : every == 1                     ? std::string("every frame")
                                                  : fmt::format("every {} frames", every));
  } else if (wants_prior) {
    if (args.semantic_masks.empty()) {
      throw Error(fmt::format("mode {} needs a semantic prior, but the network is off (semantic.network in {}) and "
                              "no --semantic-masks is given", ToString(options.dynamic.mode), args.config.string()));
    }
    prior_source = MakeSemanticPriorSource(args.semantic_masks, sequence);
    spdlog::info("semantic prior: {}", prior_source->Describe());
  } else if (!args.semantic_masks.empty()) {
    spdlog::warn("--semantic-masks is not used in mode {}", ToString(options.dynamic.mode));
  }
  if (!wants_prior && !args.semantic_model.empty()) {
    spdlog::warn("--semantic-model is not used in mode {}", ToString(options.dynamic.mode));
  }
  SlamSystem slam(camera, options);
  StageTimings source_timings;  // the prior source's own time: stage "semantic"
  std::optional<double> map_load_ms;
  if (!args.load_map.empty()) {
    const Stopwatch watch;
    slam.LoadMap(args.load_map);
    map_load_ms = watch.ElapsedMs();
  }

  const std::size_t n = args.max_frames ? std::min(args.max_frames, sequence.size()) : sequence.size();
  TrackingState last_state = TrackingState::kNotInitialized;
  // The folder's name, also for "seq/" (filename() of that is empty).
  const std::string title = (args.sequence / "").parent_path().filename().string();
  std::unique_ptr<LiveView> live;
  if (args.view_port >= 0) {
    live = std::make_unique<LiveView>(args.view_port, title, ToString(options.dynamic.mode), &slam);
    spdlog::info("live view on http://127.0.0.1:{}/", live->port());
  }
  int posed = 0;
  // Frames are read ahead in a thread of their own, as a camera delivers them.
  const Stopwatch loop_watch;
  io::FramePrefetcher frames(sequence, n);
  const auto timestamp_of = [&](std::size_t i) { return sequence.frames()[i].timestamp(); };
  std::optional<io::LivePlayback> live_camera;
  if (args.realtime_rate > 0) live_camera.emplace(args.realtime_rate, timestamp_of(0));
  // The network starts on the next frame while this one is tracked (not
  // live: a live camera has not delivered it yet).
  const auto segment_ahead = [&](const std::optional<io::FramePrefetcher::Item>& item) {
    if (item && item->result.ok() && !prior_source && !live_camera) {
      slam.SegmentAhead(item->result.frame->color, item->result.frame->timestamp);
    }
  };
  std::optional<io::FramePrefetcher::Item> next = frames.Next();
  segment_ahead(next);
  while (std::optional<io::FramePrefetcher::Item> item = std::exchange(next, frames.Next())) {
    const std::size_t i = item->index;
    segment_ahead(next);
    if (live_camera) {
      if (i + 1 < n && live_camera->Overwritten(timestamp_of(i + 1))) {
        slam.MarkDropped(timestamp_of(i));
        continue;
      }
      live_camera->WaitForArrival(timestamp_of(i));
    }
    const io::FrameLoadResult& loaded = item->result;
    if (!loaded.ok()) {
      spdlog::warn("frame {} lost: {}", i, loaded.error);
      slam.MarkLost(sequence.frames()[i].timestamp());
      continue;
    }
    const io::RgbdFrame& f = *loaded.frame;
    DynamicInputs inputs;
    if (!f.mask.empty()) inputs.moving_truth = MovingTruthFromLabels(f.mask);
    if (prior_source) {
      inputs.semantic_prior = [&] {
        SemanticPrior prior = prior_source->Prior(i, f);
        source_timings.Add("semantic", prior.compute_ms);
        return dynamic::SemanticMasks{prior.mask, prior.movable};
      };
    }
    const TrackingResult r = slam.TrackRgbd(f.color, f.depth, f.timestamp, inputs);
    if (live_camera) source_timings.Add("latency", live_camera->MsSinceArrival(timestamp_of(i)));
    if (r.new_keyframe && options.keep_keyframe_images && !f.mask.empty()) {
      keyframe_people[f.timestamp] = ClassMaskFromLabels(f.mask, synth::kClassPerson);
    }
    if (r.relocalized) {
      spdlog::info("frame {} (t={:.6f}): tracking {} -> relocalized on keyframe {} ({} inliers)", i, f.timestamp,
                   ToString(last_state), r.relocalization_keyframe, r.inliers);
      last_state = r.state;
    } else if (r.state != last_state) {
      spdlog::info("frame {} (t={:.6f}): tracking {} -> {}", i, f.timestamp, ToString(last_state), ToString(r.state));
      last_state = r.state;
    }
    if (r.cam_from_world) ++posed;
    if (live) {
      LiveFrame frame;
      frame.frame = static_cast<int>(i + 1);
      frame.posed = posed;
      frame.state = ToString(r.state);
      frame.timestamp = f.timestamp;
      if (r.cam_from_world) {
        frame.world_from_cam = r.cam_from_world->Inverse();
        frame.position = frame.world_from_cam->translation();
      }
      if (const auto truth = sequence.ground_truth()) frame.ground_truth = PoseNear(*truth, f.timestamp);
      frame.source = PoseSourceLetter(slam.FrameSources().back().source);
      // Timings are summarised (sorted) only now and then.
      const RunStats stats = i % 15 == 0 ? slam.Stats() : RunStats();
      live->Publish(frame, f.color, slam.LastFrameView(), i % 15 == 0 ? &stats : nullptr);
    }
    if (removal_images) {
      removal_images->Write(i, sequence.frames()[i].rgb.path.stem().string(), f.color, slam.LastFrameView());
    }
    if ((i + 1) % 100 == 0) spdlog::info("{}/{} frames", i + 1, n);
  }

  slam.Shutdown();
  const double loop_ms = loop_watch.ElapsedMs();
  const Trajectory trajectory = slam.CameraTrajectory();
  io::WriteTumTrajectory(args.out, trajectory);
  spdlog::info("wrote {} poses to {}", trajectory.size(), args.out.string());
  if (!args.keyframes.empty()) io::WriteTumTrajectory(args.keyframes, slam.KeyFrameTrajectory());
  const std::filesystem::path sources_path = args.pose_sources.empty() ? PoseSourcesPath(args.out) : args.pose_sources;
  WritePoseSources(sources_path, slam.FrameSources());

  RunStats stats = slam.Stats();
  for (const auto& [stage, summary] : source_timings.Summaries()) stats.timing_ms[stage] = summary;
  if (n > 1) {
    // Frames read to Shutdown (local mapping and loop closing finished).
    const double wall_s = loop_ms / 1e3;
    const double video_s = sequence.frames()[n - 1].timestamp() - sequence.frames()[0].timestamp();
    spdlog::info("{} frames in {:.1f} s for {:.1f} s of video: {:.2f}x real time", n, wall_s, video_s,
                 wall_s > 0 ? video_s / wall_s : 0.0);
  }
  std::optional<RunEvaluation> evaluation;
  if (sequence.ground_truth()) {
    evaluation = EvaluateRun(*sequence.ground_truth(), trajectory, /*bonn=*/sequence.camera().name == "bonn");
  }
  const auto& t = stats.timing_ms;
  spdlog::info("posed {}/{} frames (tracked {}, relocalized {}, coasted {}, in a new map {}), without a pose {} (lost "
               "{}, before initialisation {}{}), {} loops closed, {} new maps ({} merged), {} keyframes, {} map points, "
               "{} jumps refused",
               stats.frames_posed(), stats.frames, stats.frames_tracked_source(), stats.relocalizations,
               stats.frames_coasted, stats.frames_new_map, stats.frames_without_pose(), stats.frames_lost,
               stats.frames_waiting,
               live_camera ? fmt::format(", dropped by the live camera {}", stats.frames_dropped) : std::string(),
               stats.loop.loops_closed, stats.maps_started, stats.maps_merged, stats.keyframes, stats.map_points,
               stats.jumps_refused);
  if (t.count("frame_total")) {
    spdlog::info("time per frame: median {:.1f} ms, p95 {:.1f} ms (ORB {:.1f} ms, tracking {:.1f} ms)",
                 t.at("frame_total").median, t.at("frame_total").p95, t.at("orb_extraction").median,
                 t.at("tracking").median);
  }
  if (t.count("latency")) {
    spdlog::info("live at {}x the camera's rate: latency from arrival to pose median {:.1f} ms, p95 {:.1f} ms",
                 args.realtime_rate, t.at("latency").median, t.at("latency").p95);
  }
  LogDynamicSummary(stats);
  if (evaluation) {
    spdlog::info("ATE RMSE {:.4f} m over {} poses", evaluation->ate.error.rmse, evaluation->ate.pairs);
    if (evaluation->rpe) {
      spdlog::info("RPE (1 s) RMSE {:.4f} m, {:.3f} deg", evaluation->rpe->translation.rmse,
                   evaluation->rpe->rotation_deg.rmse);
    }
    if (const auto& bonn = evaluation->bonn_camera) {
      spdlog::info("against the Bonn camera poses (the published marker poses transformed, eval --gt-convention "
                   "bonn-camera): ATE RMSE {:.4f} m{}", bonn->ate.error.rmse,
                   bonn->rpe ? fmt::format(", RPE (1 s) RMSE {:.4f} m, {:.3f} deg", bonn->rpe->translation.rmse,
                                             bonn->rpe->rotation_deg.rmse)
                               : std::string());
    }
  }
  std::optional<double> map_save_ms;
  if (!args.save_map.empty()) {
    const Stopwatch watch;
    slam.SaveMap(args.save_map);
    map_save_ms = watch.ElapsedMs();
    spdlog::info("saved map {}: {} keyframes, {} map points, {:.1f} MB in {:.0f} ms", args.save_map.string(),
                 stats.keyframes, stats.map_points, static_cast<double>(std::filesystem::file_size(args.save_map)) / 1e6,
                 *map_save_ms);
  }
  std::optional<DenseMapResult> dense_map;
  if (!args.dense_map.empty()) dense_map = WriteDenseMap(slam, dense_options, keyframe_people, args.dense_map, args.dense_with_dynamic);
  if (!args.report.empty()) {
    nlohmann::ordered_json report = MakeRunReport(stats, evaluation);
    if (dense_map) report["dense_map"] = DenseMapReport(*dense_map);
    report["config_file"] = args.config.empty() ? nullptr : nlohmann::ordered_json(args.config.string());
    // 0: as fast as possible; else the live camera's speed (--realtime).
    report["realtime_rate"] = args.realtime_rate;
    report["options"] = config::ConfigJson(run_options);
    if (!args.load_map.empty() || map_save_ms) {
      nlohmann::ordered_json m;
      m["loaded"] = args.load_map.empty() ? nullptr : nlohmann::ordered_json(args.load_map.string());
      m["load_ms"] = OrNull(map_load_ms);
      m["localization_only"] = args.localize;
      m["saved"] = map_save_ms ? nlohmann::ordered_json(args.save_map.string()) : nullptr;
      m["save_ms"] = OrNull(map_save_ms);
      m["saved_bytes"] = map_save_ms ? nlohmann::ordered_json(std::filesystem::file_size(args.save_map)) : nullptr;
      report["map_file"] = m;
    }
    const std::string text = report.dump(2) + "\n";
    io::WriteFileAtomically(args.report, [&](std::ostream& out) { out << text; });
    spdlog::info("wrote report {}", args.report.string());
  }
  if (!args.html.empty()) {
    WriteHtmlReport(args.html, {title, &slam, &stats, &evaluation, config::ConfigJson(run_options)});
    spdlog::info("wrote {}", args.html.string());
  }
  // Everything is written before the view lingers: an interrupt then loses nothing.
  if (live && args.view_linger_s > 0) {
    spdlog::info("live view: the run is done and its files written; serving for {} s more", args.view_linger_s);
    std::this_thread::sleep_for(std::chrono::duration<double>(args.view_linger_s));
  }
  if (live) live->Stop();
  return {stats, evaluation};
}

void AddRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Run SLAM on an RGB-D sequence folder (TUM layout)");
  cmd->add_option("--sequence", args->sequence, "Sequence folder (rgb.txt, depth.txt, ...)")->required();
  cmd->add_option("--config", args->config,
                  "Every option of every module from one YAML file (dlslam config dump writes one with the "
                  "defaults); flags given here override it; ORB-SLAM3 camera keys in it set the camera");
  cmd->add_option("--out", args->out, "Camera trajectory output (TUM format)")->capture_default_str();
  cmd->add_option("--keyframes", args->keyframes, "Keyframe trajectory output (TUM format)");
  cmd->add_option("--pose-sources", args->pose_sources,
                  "How each frame's pose was obtained (timestamp tracked|relocalized|coasted|new_map|none); default: beside "
                  "--out, traj.txt -> traj.sources.txt");
  cmd->add_option("--report", args->report, "JSON report: frames, tracking, timing, ATE/RPE");
  cmd->add_flag("--view{8090}", args->view_port,
                "Serve the run live on http://127.0.0.1:PORT/ (--view for 8090, or --view=PORT): the frame with kept "
                "and removed keypoints, trajectory, 3-D map, timings, state")
      ->check(WholeNumber(1, 65535));
  cmd->add_option("--view-linger", args->view_linger_s, "Keep the live view up this long after the run [s]")
      ->check(RealNumber(0, 86400));
  cmd->add_option("--removal-images", args->removal_images,
                  "Write each frame as the dynamic stage saw it into this new or empty folder (<colour image "
                  "name>.jpg): the network's removal tinted red, geometry's blue, kept keypoints green, removed "
                  "ones yellow");
  cmd->add_option("--removal-images-every", args->removal_images_every,
                  "With --removal-images: every k-th frame")
      ->capture_default_str()
      ->check(WholeNumber(1, 1000000));
  cmd->add_option("--html", args->html,
                  "The run as one self-contained web page: trajectory vs ground truth, error over time, the map "
                  "in 3-D, timings, options");
  cmd->add_option("--mode", args->mode,
                  "orb: the ORB-SLAM3-style baseline; semantic: drop keypoints on the semantic prior; "
                  "geometry: multi-view geometry finds moving regions; full: both, fused")
      ->capture_default_str()
      ->check(CLI::IsMember({"orb", "semantic", "geometry", "full"}));
  cmd->add_option("--geometry-search", args->geometry_search,
                  "Which projected points geometry tests: exhaustive (all) or ant (the ant colony search)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exhaustive", "ant"}));
  cmd->add_option("--fusion", args->fusion,
                  "Mode full: union (prior or geometry), geometry-confirms (keep prior segments geometry "
                  "shows still), semantic, geometry")
      ->capture_default_str()
      ->check(CLI::IsMember({"union", "geometry-confirms", "geometry_confirms", "semantic", "geometry"}));
  cmd->add_option("--semantic-masks", args->semantic_masks,
                  "Semantic prior for modes semantic/full instead of the segmentation network: gt (the "
                  "sequence's ground-truth masks: class person, and other movable objects as movable) or a "
                  "folder of PNG masks named like the colour images (non-zero = dynamic)");
  cmd->add_option("--semantic-model", args->semantic_model,
                  "Segmentation network (ONNX) for modes semantic/full; default: the shipped model");
  cmd->add_option("--segment-every", args->segment_every,
                  "Segment every k-th frame, propagating the mask to the frames between")
      ->capture_default_str()
      ->check(WholeNumber(1, 100));
  cmd->add_flag("--async-masks", args->async_masks,
                "Modes semantic, full (experimental): never wait for the network; use its newest masks, carried to "
                "each frame with the camera motion and depth");
  cmd->add_flag("--sequential", args->sequential,
                "Run local mapping inline: deterministic, reproducible bit for bit");
  cmd->add_flag("--realtime{1}", args->realtime_rate,
                "Play the sequence as a live camera delivers it: each frame at its timestamp (--realtime=RATE: "
                "at RATE x the camera's speed); a frame the system had no time for is overwritten by the next "
                "(dropped, no pose). Reports the latency from arrival to pose")
      ->check(RealNumber(0.01, 100));
  cmd->add_flag("--no-relocalization", args->no_relocalization, "Do not relocalize a lost camera");
  cmd->add_flag("--no-loop", args->no_loop, "Do not close loops (for comparisons)");
  cmd->add_flag("--no-movables", args->no_movables,
                "Mode full: keep movable-class segments (chairs) whole even when geometry sees them move "
                "(only geometry's own region around the moving points goes; for comparisons)");
  cmd->add_option("--vocabulary", args->vocabulary,
                  "Bag-of-words vocabulary (.dlv) for relocalization and loop closing; default: the shipped one");
  cmd->add_option("--bundle-solver", args->bundle_solver,
                  "Local bundle adjustment: lm (our sparse Levenberg-Marquardt) or ceres")
      ->capture_default_str()
      ->check(CLI::IsMember({"lm", "ceres"}));
  cmd->add_option("--max-frames", args->max_frames, "Stop after this many frames (0 = all)")->check(WholeNumber(0, 1000000000));
  cmd->add_option("--save-map", args->save_map,
                  "Write the map at the end (keyframes, features, map points, covisibility; binary, versioned, "
                  "checksummed .dlmap) for --load-map");
  cmd->add_option("--load-map", args->load_map,
                  "Start in a saved map (relocalizing in it) and continue mapping on top of it; with --localize, "
                  "track in it without adding keyframes");
  cmd->add_flag("--localize", args->localize, "Localization only, in the --load-map map: no keyframes added");
  cmd->add_option("--dense-map", args->dense_map,
                  "Write the dense static model (keyframes' depth fused at their final poses into a TSDF, the "
                  "removed dynamic regions left out) as a coloured PLY point cloud");
  cmd->add_option("--dense-voxel", args->dense_voxel, "Voxel size of the dense model [m]")
      ->capture_default_str()
      ->check(RealNumber(0.005, 0.5));
  cmd->add_flag("--dense-with-dynamic", args->dense_with_dynamic,
                "Fuse the removed dynamic regions into the dense model too (for comparisons)");
  cmd->add_option("--camera", args->sequence_options.camera_preset, "Camera preset: fr1, fr2, fr3, bonn");
  cmd->add_option("--settings", args->sequence_options.settings_file, "ORB-SLAM3-style settings YAML");
  cmd->add_option("--depth-factor", args->sequence_options.depth_factor, "Raw depth units per metre")->check(RealNumber(kMinDepthFactor, kMaxDepthFactor));
  cmd->add_option("--associations", args->sequence_options.associations_file, "RGB-depth association file");
  cmd->callback([args, cmd] {
    args->given = GivenFlags(*cmd);
    // CLI11 sets an integer flag it was not given to 0 (a count): without
    // this every run served a live view on a random port.
    if (args->given.count("--view") == 0) args->view_port = -1;
    RunSequence(*args);
  });
}

}  // namespace dlslam::app
