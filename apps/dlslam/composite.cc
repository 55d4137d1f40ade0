// dlslam composite: a semi-real dynamic sequence from a real static one:
// photos of people (cut out by their masks) walk through a recording with
// ground-truth poses (synth/composite.h); writes the TUM layout with
// ground-truth person masks, as `dlslam synth` does.
//
//   dlslam composite --background ../shared/data/7scenes-redkitchen-500
//                    --people ../shared/data/segmentation/ccp-person --out kitchen_people

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "commands.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/sequence.h"
#include "dlslam/io/sequence_writer.h"
#include "dlslam/synth/camera_path.h"
#include "dlslam/synth/composite.h"
#include "dlslam/util/check.h"

namespace dlslam::app {

namespace fs = std::filesystem;

namespace {

struct CompositeArgs {
  fs::path background;
  fs::path people;
  fs::path out;
  bool force = false;
  std::size_t max_frames = 0;
  synth::CompositeOptions options;
};

// `count` photos of DIR/images with a mask of the same name in DIR/masks
// (PNG), chosen by the seed.
std::vector<synth::Cutout> LoadCutouts(const fs::path& dir, int count, unsigned seed) {
  const fs::path images = dir / "images", masks = dir / "masks";
  if (!fs::is_directory(images) || !fs::is_directory(masks)) {
    throw InputError(dir, 0, "needs images/ (photos) and masks/ (PNG masks of the same names)");
  }
  std::vector<fs::path> photos;
  for (const auto& entry : fs::directory_iterator(images)) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".jpg" || ext == ".jpeg" || ext == ".png") &&
        fs::is_regular_file(masks / (entry.path().stem().string() + ".png"))) {
      photos.push_back(entry.path());
    }
  }
  if (photos.empty()) throw InputError(images, 0, "holds no photo with a mask in {}", masks.string());
  std::sort(photos.begin(), photos.end());
  std::mt19937 rng(seed);
  std::shuffle(photos.begin(), photos.end(), rng);
  std::vector<synth::Cutout> cutouts;
  for (const fs::path& photo : photos) {
    if (static_cast<int>(cutouts.size()) == count) break;
    synth::Cutout c;
    c.name = photo.filename().string();
    c.bgr = io::ReadColorImage({photo, {}, 0}, 0, 0);
    const fs::path mask = masks / (photo.stem().string() + ".png");
    c.mask = io::ReadMaskImage({mask, {}, 0}, c.bgr.cols, c.bgr.rows);
    if (cv::countNonZero(c.mask) < 200) {
      spdlog::warn("{}: mask holds almost no person, skipped", mask.string());
      continue;
    }
    cutouts.push_back(std::move(c));
  }
  if (cutouts.empty()) throw InputError(masks, 0, "no usable person mask");
  return cutouts;
}

void RunComposite(const CompositeArgs& args) {
  args.options.Check();
  const io::RgbdSequence sequence = io::RgbdSequence::Open(args.background);
  if (!sequence.ground_truth()) {
    throw InputError(args.background, 0, "has no groundtruth.txt: the people are placed in the world, so the "
                                         "background needs camera poses");
  }
  const Trajectory& truth = *sequence.ground_truth();
  std::vector<synth::Cutout> cutouts = LoadCutouts(args.people, args.options.people, args.options.seed);
  const std::size_t n = args.max_frames ? std::min(args.max_frames, sequence.size()) : sequence.size();
  Trajectory camera_path;  // the frames' poses, where the walkers are laid out
  for (std::size_t i = 0; i < n; ++i) {
    const double t = sequence.frames()[i].timestamp();
    if (const std::optional<SE3d> pose = synth::InterpolatePose(truth, t)) camera_path.emplace_back(t, *pose);
  }
  if (camera_path.empty()) throw InputError(args.background, 0, "no frame lies inside the ground truth's time span");
  const synth::PeopleCompositor people(sequence.camera(), cutouts, args.options, camera_path);
  io::SequenceWriterOptions write;
  write.description = fmt::format("dlslam composite background={} people={} count={} seed={}",
                                  args.background.filename().string(), args.people.filename().string(),
                                  args.options.people, args.options.seed);
  write.force = args.force;
  io::SequenceWriter writer(args.out, sequence.camera(), write);
  double covered_sum = 0, covered_max = 0;
  int skipped = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const io::FrameLoadResult loaded = sequence.TryLoadFrame(i);
    if (!loaded.ok()) {
      spdlog::warn("frame {} skipped: {}", i, loaded.error);
      ++skipped;
      continue;
    }
    const io::RgbdFrame& f = *loaded.frame;
    const std::optional<SE3d> world_from_cam = synth::InterpolatePose(truth, f.timestamp);
    if (!world_from_cam) {
      spdlog::warn("frame {} (t={:.6f}) skipped: outside the ground truth's time span", i, f.timestamp);
      ++skipped;
      continue;
    }
    const synth::CompositedFrame c = people.Composite(f.timestamp, *world_from_cam, f.color, f.depth);
    writer.Add(f.timestamp, c.colour, c.depth, c.mask, *world_from_cam);
    covered_sum += c.person_share;
    covered_max = std::max(covered_max, c.person_share);
    if ((i + 1) % 100 == 0) spdlog::info("{} / {} frames", i + 1, n);
  }
  if (writer.frames() == 0) throw InputError(args.background, 0, "no frame could be composited");
  writer.Finish();
  fmt::print("wrote {} frames to {} ({} skipped): {} people, covering {:.1f} % of the image on average, {:.1f} % "
             "at most\n",
             writer.frames(), args.out.string(), skipped, people.walkers(), 100 * covered_sum / writer.frames(),
             100 * covered_max);
}

}  // namespace

void AddCompositeCommand(CLI::App& app) {
  auto args = std::make_shared<CompositeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "composite", "Walk real photos of people through a real static RGB-D sequence with poses (semi-real data)");
  cmd->add_option("--background", args->background, "Static sequence folder with groundtruth.txt")->required();
  cmd->add_option("--people", args->people, "Folder with images/ (photos of people) and masks/ (PNG, same names)")
      ->required();
  cmd->add_option("--out", args->out, "Output folder (TUM layout with mask.txt; refuses a non-empty folder)")
      ->required();
  cmd->add_flag("--force", args->force, "Write into a non-empty folder anyway (deletes nothing)");
  cmd->add_option("--frames", args->max_frames, "At most this many frames (0 = all)")->check(WholeNumber(0, 1000000000));
  synth::CompositeOptions& o = args->options;
  cmd->add_option("--count", o.people, "People walking at once")->capture_default_str()->check(WholeNumber(1, 20));
  cmd->add_option("--seed", o.seed, "Seed: photos, distances, directions")->capture_default_str()->check(WholeNumber(0, 4294967295));
  cmd->add_option("--min-distance", o.min_distance_m, "Nearest walking line in front of the first camera [m]")
      ->capture_default_str()->check(RealNumber(0.3, 100));
  cmd->add_option("--max-distance", o.max_distance_m, "Farthest walking line [m]")->capture_default_str()->check(RealNumber(0.3, 100));
  cmd->add_option("--speed", o.speed_mps, "Walking speed [m/s]")->capture_default_str()->check(RealNumber(0, 10));
  cmd->add_option("--path-length", o.path_length_m, "Length of the line walked back and forth [m]")
      ->capture_default_str()->check(RealNumber(0.1, 100));
  cmd->add_option("--height", o.height_m, "Person height [m]")->capture_default_str()->check(RealNumber(0.5, 3));
  cmd->callback([args] { RunComposite(*args); });
}

}  // namespace dlslam::app
