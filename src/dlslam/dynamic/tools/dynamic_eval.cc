// Measures the geometry check (multi-view depth test + search strategy +
// region growing) on rendered synthetic sequences with ground-truth poses,
// and draws it on real frame pairs:
//
//   build/bin/dynamic_eval --presets walking_xyz,walking_static --frames 60
//   build/bin/dynamic_eval --presets walking_xyz --pictures out/   # + overlay PNGs
//   build/bin/dynamic_eval --real-pair "../shared/data/real-samples/jointvosf_dynamic_frame_pairs/two people walking" --pictures out/
//   build/bin/dynamic_eval --tum-pair ../shared/data/real-samples/tum_walking_xyz_3frames --swap
//       --groundtruth ../shared/data/tum/gt/rgbd_dataset_freiburg3_walking_xyz.txt
//
// Synthetic: per preset and strategy, keypoints (reference points) projected
// and tested per frame, precision / recall of the final mask over the current
// frame's ORB keypoints (truth: synth MaskMoving) and Detect() time.
// Real pairs: frame 0 is the reference keyframe, frame 1 the current frame;
// without ground truth the relative pose comes from ORB matches with depth
// (RANSAC over 3-point Horn alignments, then a refit on the inliers).

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dlslam/dynamic/tools/keyframe_eval.h"
#include "dlslam/eval/horn.h"
#include "dlslam/features/matching.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/camera_path.h"
#include "dlslam/util/check.h"

namespace fs = std::filesystem;
using namespace dlslam;
using namespace dlslam::dynamic;

namespace {

std::vector<std::string> Split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// The colour frame with the final mask tinted red and the projected
// reference points: red = dynamic, magenta = vanished, green = static,
// grey = unknown / unreliable, blue dot = not tested (skipped).
cv::Mat DrawOverlay(const cv::Mat& colour, const GeometryResult& result, const cv::Mat& mask,
                    double scale) {
  cv::Mat out = colour.clone();
  cv::Mat tint(out.size(), CV_8UC3, cv::Scalar(0, 0, 255));
  cv::Mat blended;
  cv::addWeighted(out, 0.55, tint, 0.45, 0, blended);
  blended.copyTo(out, mask);
  for (std::size_t i = 0; i < result.points.size(); ++i) {
    const cv::Point p(static_cast<int>(std::lround(result.points[i].pixel.x())),
                      static_cast<int>(std::lround(result.points[i].pixel.y())));
    switch (result.labels[i]) {
      case PointLabel::kDynamic: cv::circle(out, p, 4, {0, 0, 255}, cv::FILLED); break;
      case PointLabel::kVanished: cv::circle(out, p, 4, {255, 0, 255}, cv::FILLED); break;
      case PointLabel::kStatic: cv::circle(out, p, 3, {0, 200, 0}, 1); break;
      case PointLabel::kUnknown:
      case PointLabel::kOccluded:
      case PointLabel::kUnreliable: cv::circle(out, p, 3, {160, 160, 160}, 1); break;
      case PointLabel::kUntested: cv::circle(out, p, 1, {255, 128, 0}, cv::FILLED); break;
    }
  }
  if (scale != 1.0) cv::resize(out, out, cv::Size(), scale, scale, cv::INTER_AREA);
  return out;
}

void WritePicture(const fs::path& dir, const std::string& name, const cv::Mat& image) {
  fs::create_directories(dir);
  const fs::path path = dir / name;
  DLSLAM_CHECK(cv::imwrite(path.string(), image, {cv::IMWRITE_PNG_COMPRESSION, 9}),
               "cannot write {}", path.string());
  fmt::print("wrote {} ({} KB)\n", path.string(), fs::file_size(path) / 1024);
}

// 3-D points of matched keypoints with depth in both frames.
struct Correspondences {
  std::vector<Eigen::Vector3d> in0, in1;  // camera frames 0 and 1
};

Correspondences Match3d(const features::OrbFeatures& f0, const features::OrbFeatures& f1,
                        const cv::Mat& depth0, const cv::Mat& depth1,
                        const CameraIntrinsics& camera) {
  Correspondences c;
  for (const cv::DMatch& m : features::MatchBruteForce(f1.descriptors, f0.descriptors)) {
    const cv::Point2f p0 = f0.keypoints[static_cast<std::size_t>(m.trainIdx)].pt;
    const cv::Point2f p1 = f1.keypoints[static_cast<std::size_t>(m.queryIdx)].pt;
    const double z0 = depth0.at<float>(cvRound(p0.y), cvRound(p0.x));
    const double z1 = depth1.at<float>(cvRound(p1.y), cvRound(p1.x));
    if (!(z0 > 0.1 && z0 < 6 && z1 > 0.1 && z1 < 6)) continue;
    c.in0.push_back(camera.Unproject({p0.x, p0.y}, z0));
    c.in1.push_back(camera.Unproject({p1.x, p1.y}, z1));
  }
  return c;
}

// cam1_from_cam0 by RANSAC over minimal Horn alignments (the static scene is
// the largest rigid set of matches), refit on the inliers.
SE3d EstimateRelativePose(const Correspondences& c, int* inliers_out) {
  DLSLAM_CHECK_GE(c.in0.size(), 10u, "too few matches with depth to estimate the pose");
  std::mt19937 rng(1);
  std::uniform_int_distribution<std::size_t> pick(0, c.in0.size() - 1);
  const auto inliers_of = [&](const dlslam::eval::RigidAlignment& a) {
    std::vector<std::size_t> in;
    for (std::size_t i = 0; i < c.in0.size(); ++i) {
      const double tolerance = 0.02 + 0.01 * c.in1[i].z() * c.in1[i].z();
      if ((a.Apply(c.in0[i]) - c.in1[i]).norm() < tolerance) in.push_back(i);
    }
    return in;
  };
  std::vector<std::size_t> best;
  for (int iteration = 0; iteration < 500; ++iteration) {
    std::vector<Eigen::Vector3d> a(3), b(3);
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = pick(rng);
      a[static_cast<std::size_t>(k)] = c.in0[i];
      b[static_cast<std::size_t>(k)] = c.in1[i];
    }
    std::vector<std::size_t> in = inliers_of(dlslam::eval::AlignHorn(a, b));
    if (in.size() > best.size()) best.swap(in);
  }
  for (int refit = 0; refit < 2; ++refit) {
    std::vector<Eigen::Vector3d> a, b;
    for (const std::size_t i : best) {
      a.push_back(c.in0[i]);
      b.push_back(c.in1[i]);
    }
    best = inliers_of(dlslam::eval::AlignHorn(a, b));
  }
  std::vector<Eigen::Vector3d> a, b;
  for (const std::size_t i : best) {
    a.push_back(c.in0[i]);
    b.push_back(c.in1[i]);
  }
  const dlslam::eval::RigidAlignment fit = dlslam::eval::AlignHorn(a, b);
  *inliers_out = static_cast<int>(best.size());
  return SE3d(SO3d(fit.rotation), fit.translation);
}

struct PairRun {
  std::string name;
  cv::Mat colour1;
  cv::Mat depth0, depth1;
  features::OrbFeatures f0;
  SE3d world_from_cam0, world_from_cam1;
};

void RunPair(const PairRun& pair, const CameraIntrinsics& camera, const GeometryOptions& options,
             const std::string& pictures, double scale) {
  const ReferenceView reference =
      evaluation::MakeReferenceView(pair.depth0, pair.f0.keypoints, camera, pair.world_from_cam0, 0);
  for (const SearchKind kind : {SearchKind::kExhaustive, SearchKind::kAntColony}) {
    GeometryOptions o = options;
    o.search = kind;
    GeometryDetector detector(o);
    const GeometryResult r =
        detector.Detect(pair.depth1, camera, pair.world_from_cam1.Inverse(), {reference});
    const cv::Mat mask = FuseDynamicMasks({}, r, evaluation::SynthEvalOptions{}.fusion);
    fmt::print("{:<24} {:<10} projected {:4d} tested {:4d} dynamic {:4d} vanished {:4d} mask {:5.1f}%\n",
               pair.name, ToString(kind), r.points_projected, r.points_tested, r.points_dynamic,
               r.points_vanished, 100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total()));
    if (!pictures.empty()) {
      std::string file = pair.name + "_" + ToString(kind) + ".png";
      std::replace(file.begin(), file.end(), ' ', '_');
      WritePicture(pictures, file, DrawOverlay(pair.colour1, r, mask, scale));
    }
  }
}

io::ImageSource Source(const fs::path& image) {
  io::ImageSource source;
  source.image = image;
  return source;
}

std::vector<fs::path> SortedFiles(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Dynamic-point detection by multi-view geometry: accuracy and speed"};
  std::string presets = "walking_xyz,walking_static,walking_halfsphere,sitting_static";
  std::string strategies = "exhaustive,ant";
  std::string pictures, real_pair, tum_pair, groundtruth;
  int seed = 1;
  double picture_scale = 0.5;
  evaluation::SynthEvalOptions eval_options;
  GeometryOptions geometry;
  app.add_option("--presets", presets, "comma-separated synth presets");
  app.add_option("--strategies", strategies, "comma-separated: exhaustive, ant");
  app.add_option("--seed", seed, "synth seed");
  app.add_option("--first", eval_options.first_frame, "first evaluated frame");
  app.add_option("--frames", eval_options.frames, "frames evaluated per preset");
  app.add_option("--step", eval_options.step, "frames between evaluated frames");
  app.add_option("--refs", eval_options.reference_count, "keyframes per frame");
  app.add_option("--ref-stride", eval_options.reference_stride, "frames between keyframes");
  app.add_option("--pictures", pictures, "folder for overlay PNGs (last frame of each run)");
  app.add_option("--picture-scale", picture_scale, "scale of the PNGs");
  app.add_option("--real-pair", real_pair, "folder with color0/1.png, depth0/1.png (no poses)");
  app.add_option("--tum-pair", tum_pair, "folder with rgb/ and depth/ (first two frames used)");
  app.add_option("--groundtruth", groundtruth, "TUM groundtruth for --tum-pair");
  bool swap = false;
  app.add_flag("--swap", swap, "pairs: frame 1 is the reference, frame 0 the current one");
  app.add_option("--radius", geometry.ant.search_radius_px, "ant colony R [px]");
  app.add_option("--skip-radius", geometry.ant.static_skip_radius_px, "ant colony static skip radius [px]");
  app.add_option("--region-reach", geometry.region.max_distance_from_seed_m, "region growing: metres from the seed (0 = no limit)");
  app.add_option("--static-reach", geometry.region.static_distance_from_seed_m, "region growing: metres a static point claims (0 = no limit)");
  app.add_option("--head-start", geometry.region.static_head_start_px, "region growing: static points start after [px]");
  app.add_option("--pixel-step", geometry.region.pixel_step, "region growing grid step (1, 2)");
  app.add_flag("!--no-static-barriers", geometry.region.static_points_compete, "region growing: static points do not compete");
  app.add_flag("!--no-vanished-barriers", geometry.vanished_as_barriers, "vanished points are no barriers");
  app.add_option("--band", geometry.ant.band_width_px, "ant colony dh [px]");
  app.add_option("--depth-threshold", geometry.multiview.depth_threshold_m, "th(0) [m]");
  CLI11_PARSE(app, argc, argv);
  geometry.Check();

  if (!real_pair.empty() || !tum_pair.empty()) {
    CameraIntrinsics camera = tum_pair.empty() ? CameraIntrinsics{} : CameraPreset("freiburg3");
    features::OrbExtractor orb;
    PairRun pair;
    cv::Mat colour0;
    if (!real_pair.empty()) {
      const fs::path dir = real_pair;
      pair.name = dir.filename().string();
      colour0 = io::ReadColorImage(Source(dir / "color0.png"), camera.width, camera.height);
      pair.colour1 = io::ReadColorImage(Source(dir / "color1.png"), camera.width, camera.height);
      pair.depth0 = io::ReadDepthImage(Source(dir / "depth0.png"), camera.depth_factor, camera.width, camera.height);
      pair.depth1 = io::ReadDepthImage(Source(dir / "depth1.png"), camera.depth_factor, camera.width, camera.height);
    } else {
      const fs::path dir = tum_pair;
      pair.name = "tum_" + dir.filename().string();
      const auto rgb = SortedFiles(dir / "rgb"), depth = SortedFiles(dir / "depth");
      DLSLAM_CHECK(rgb.size() >= 2 && depth.size() >= 2, "{}: need two rgb and depth images", tum_pair);
      colour0 = io::ReadColorImage(Source(rgb[0]), camera.width, camera.height);
      pair.colour1 = io::ReadColorImage(Source(rgb[1]), camera.width, camera.height);
      pair.depth0 = io::ReadDepthImage(Source(depth[0]), camera.depth_factor, camera.width, camera.height);
      pair.depth1 = io::ReadDepthImage(Source(depth[1]), camera.depth_factor, camera.width, camera.height);
      if (!groundtruth.empty()) {
        const Trajectory gt = io::ReadTumTrajectory(groundtruth);
        const auto pose_at = [&](const fs::path& image) {
          const double t = std::stod(image.stem().string());
          const auto pose = synth::InterpolatePose(gt, t);
          if (pose) return *pose;
          // Just outside the ground truth (the TUM sample's first frame is
          // 46 ms before it): the nearest end pose, within 50 ms.
          const StampedPose& end = t < gt.front().timestamp ? gt.front() : gt.back();
          DLSLAM_CHECK(std::abs(end.timestamp - t) < 0.05, "{}: no ground truth near {}",
                       groundtruth, t);
          return end.world_from_cam();
        };
        pair.world_from_cam0 = pose_at(rgb[0]);
        pair.world_from_cam1 = pose_at(rgb[1]);
      }
    }
    if (swap) {  // e.g. the TUM sample, whose second frame has the people removed
      std::swap(colour0, pair.colour1);
      std::swap(pair.depth0, pair.depth1);
      std::swap(pair.world_from_cam0, pair.world_from_cam1);
    }
    pair.f0 = orb.Extract(colour0);
    if (groundtruth.empty()) {
      const features::OrbFeatures f1 = orb.Extract(pair.colour1);
      int inliers = 0;
      const SE3d cam1_from_cam0 = EstimateRelativePose(
          Match3d(pair.f0, f1, pair.depth0, pair.depth1, camera), &inliers);
      pair.world_from_cam1 = cam1_from_cam0.Inverse();
      fmt::print("{}: relative pose from {} RANSAC inliers: |t| = {:.3f} m, angle = {:.2f} deg\n",
                 pair.name, inliers, cam1_from_cam0.translation().norm(),
                 cam1_from_cam0.so3().Log().norm() * 180.0 / M_PI);
    }
    RunPair(pair, camera, geometry, pictures, picture_scale);
    return 0;
  }

  fmt::print("{:<20} {:<10} {:>6} {:>10} {:>8} {:>7} {:>8} {:>9} {:>9} {:>7} {:>9}\n", "preset",
             "strategy", "frames", "projected", "tested", "tested%", "dynamic", "pt.prec.",
             "precision", "recall", "ms/frame");
  for (const std::string& preset_name : Split(presets)) {
    synth::SynthOptions synth_options;
    synth_options.preset = synth::ParsePreset(preset_name);
    synth_options.seed = static_cast<std::uint32_t>(seed);
    synth_options.frames = eval_options.first_frame + eval_options.frames * eval_options.step;
    const synth::SynthSequence sequence(synth_options);
    evaluation::SynthFrameCache cache(sequence);
    for (const std::string& strategy : Split(strategies)) {
      GeometryOptions o = geometry;
      o.search = ParseSearchKind(strategy);
      const evaluation::SynthEvalStats s = evaluation::EvaluateOnSynth(cache, o, eval_options);
      const double n = s.frames;
      fmt::print("{:<20} {:<10} {:>6} {:>10.0f} {:>8.0f} {:>6.1f}% {:>8.1f} {:>9.3f} {:>9.3f} {:>7.3f} {:>9.2f}\n",
                 preset_name, strategy, s.frames, s.points_projected / n, s.points_tested / n,
                 100.0 * static_cast<double>(s.points_tested) / static_cast<double>(s.points_projected),
                 s.points_dynamic / n,
                 s.points_dynamic > 0 ? static_cast<double>(s.dynamic_on_movers) / static_cast<double>(s.points_dynamic) : 1.0,
                 s.scores.Precision(), s.scores.Recall(), s.detect_ms / n);
      if (!pictures.empty()) {
        const int last = eval_options.first_frame + (eval_options.frames - 1) * eval_options.step;
        WritePicture(pictures, fmt::format("{}_{}.png", preset_name, strategy),
                     DrawOverlay(cache.Get(last).rendered.colour, s.last_result, s.last_mask,
                                 picture_scale));
      }
    }
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "[error] {}\n", e.what());
  return 1;
}
