// Learns the 256 ORB tests from real images (see pattern_learning.h and
// docs/features.md) and writes them as a C++ header:
//
//   build/bin/learn_orb_pattern --train ../shared/data/segmentation/human-seg/images ...
//     --eval ../shared/data/7scenes-redkitchen-500/rgb --eval-every 10
//     --out src/dlslam/features/orb_pattern_learned.h
// (the exact command is in the generated header's comment)
//
// Patches come from keypoints of our own extractor, rotated to their
// orientation; --eval images are held out and only scored.

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "dlslam/features/orb_extractor.h"
#include "dlslam/features/pattern_learning.h"
#include "dlslam/io/file_util.h"
#include "dlslam/util/check.h"

namespace fs = std::filesystem;
using namespace dlslam::features;

namespace {

// Every `every`-th .jpg / .png of each folder, sorted by name.
std::vector<fs::path> ListImages(const std::vector<std::string>& dirs, int every) {
  std::vector<fs::path> out;
  for (const std::string& dir : dirs) {
    if (!fs::is_directory(dir)) throw dlslam::InputError(dir, 0, "not a folder of images");
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".jpg" || ext == ".jpeg" || ext == ".png") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (size_t i = 0; i < files.size(); i += static_cast<size_t>(every)) out.push_back(files[i]);
  }
  return out;
}

// Up to `per_image` random keypoints of each image, as oriented patches.
OrientedPatches CollectPatches(const std::vector<fs::path>& images, int per_image, int max_side,
                               std::mt19937& rng) {
  OrientedPatches patches;
  OrbExtractor extractor;
  cv::Mat grey;
  for (const fs::path& path : images) {
    const cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    if (image.empty()) throw dlslam::InputError(path, 0, "cannot read the image");
    // Bring large photos to camera-like resolution (keypoint scales as at run time).
    const double shrink = std::min(1.0, static_cast<double>(max_side) / std::max(image.cols, image.rows));
    if (shrink < 1.0) {
      cv::resize(image, grey, cv::Size(), shrink, shrink, cv::INTER_AREA);
    } else {
      grey = image;
    }
    if (std::min(grey.cols, grey.rows) <= 2 * extractor.options().edge_border) continue;
    std::vector<cv::KeyPoint> keypoints = extractor.Extract(grey).keypoints;
    std::shuffle(keypoints.begin(), keypoints.end(), rng);
    if (keypoints.size() > static_cast<size_t>(per_image)) keypoints.resize(static_cast<size_t>(per_image));
    for (const cv::KeyPoint& kp : keypoints) {
      const double scale = extractor.level_scales()[static_cast<size_t>(kp.octave)];
      patches.Add(extractor.smoothed_pyramid()[static_cast<size_t>(kp.octave)],
                  static_cast<int>(std::lround(kp.pt.x / scale)),
                  static_cast<int>(std::lround(kp.pt.y / scale)), kp.angle);
    }
  }
  return patches;
}

std::string Describe(const PatternStatistics& s) {
  return fmt::format("mean bit {:.3f}, mean |bit mean - 0.5| {:.3f}, mean |corr| {:.3f}, max |corr| {:.3f}",
                     s.mean_bit, s.mean_abs_bias, s.mean_abs_correlation, s.max_abs_correlation);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Learn the ORB test pattern from images"};
  std::vector<std::string> train_dirs, eval_dirs;
  std::string out_path;
  int train_every = 1, eval_every = 10, per_image = 20, max_side = 640;
  PatternLearningOptions learn;
  app.add_option("--train", train_dirs, "folders of training images")->required();
  app.add_option("--eval", eval_dirs, "folders of held-out images, only scored");
  app.add_option("--out", out_path, "header to write (none: print statistics only)");
  app.add_option("--train-every", train_every, "use every n-th training image")->check(CLI::PositiveNumber);
  app.add_option("--eval-every", eval_every, "use every n-th held-out image")->check(CLI::PositiveNumber);
  app.add_option("--keypoints-per-image", per_image, "random keypoints per image")->check(CLI::PositiveNumber);
  app.add_option("--max-side", max_side, "shrink images to this longer side [px]")->check(CLI::PositiveNumber);
  app.add_option("--candidates", learn.candidate_tests, "candidate tests drawn (0 = all)");
  app.add_option("--min-separation", learn.min_separation, "min |dx| or |dy| of a test [px]");
  app.add_option("--initial-correlation", learn.initial_correlation, "first correlation threshold");
  app.add_option("--correlation-step", learn.correlation_step, "threshold increment");
  app.add_option("--seed", learn.seed, "random seed");
  CLI11_PARSE(app, argc, argv);

  try {
    std::mt19937 rng(learn.seed);
    const std::vector<fs::path> train_images = ListImages(train_dirs, train_every);
    const OrientedPatches train = CollectPatches(train_images, per_image, max_side, rng);
    fmt::print("training: {} images, {} patches\n", train_images.size(), train.size());
    std::fflush(stdout);
    const LearnedPattern learned = LearnPattern(train, learn);
    fmt::print("picked {} of {} candidates at |correlation| <= {:.2f}\n", learned.tests.size(),
               learned.candidates, learned.correlation_threshold);

    const std::vector<PatternTest> uniform = RandomOrbPattern(RandomPatternKind::kUniform, learn.seed);
    const std::vector<PatternTest> gaussian = RandomOrbPattern(RandomPatternKind::kGaussian, learn.seed);
    std::vector<std::string> report;
    const auto score = [&](const std::string& set, const OrientedPatches& patches) {
      for (const auto& [name, tests] : {std::pair{"learned", &learned.tests},
                                        std::pair{"random uniform", &uniform},
                                        std::pair{"random gaussian", &gaussian}}) {
        report.push_back(fmt::format("{} ({} patches), {}: {}", set, patches.size(), name,
                                     Describe(EvaluatePattern(patches, *tests))));
        fmt::print("{}\n", report.back());
      }
    };
    score("training", train);
    std::vector<fs::path> eval_images;
    if (!eval_dirs.empty()) {
      eval_images = ListImages(eval_dirs, eval_every);
      score("held-out", CollectPatches(eval_images, per_image, max_side, rng));
    }
    if (out_path.empty()) return 0;

    std::string command;
    for (int i = 0; i < argc; ++i) command += (i ? " " : "") + std::string(argv[i]);
    dlslam::io::WriteFileAtomically(out_path, [&](std::ostream& os) {
      os << "#pragma once\n"
         << "// GENERATED by src/dlslam/features/tools/learn_orb_pattern.cc; do not edit.\n"
         << "// Command (from the repository root, after a Release build):\n//   " << command << "\n"
         << fmt::format("// Training: {} images, {} oriented patches ({} random keypoints per image,\n"
                        "// images shrunk to a longer side of {} px), seed {}.\n",
                        train_images.size(), train.size(), per_image, max_side, learn.seed)
         << fmt::format("// Greedy selection over {} random candidate tests (points >= {} px apart in x or\n"
                        "// y, inside a disc of radius {}): |correlation| <= {:.2f} was reached.\n",
                        learned.candidates, learn.min_separation, kPatternRadius,
                        learned.correlation_threshold)
         << "// Bit statistics (random patterns: RandomOrbPattern with the same seed):\n";
      for (const std::string& line : report) os << "//   " << line << "\n";
      os << "\n#include \"dlslam/features/orb_pattern.h\"\n\nnamespace dlslam::features {\n\n"
         << "// {x1, y1, x2, y2}: bit = I(x1, y1) < I(x2, y2), in the order picked.\n"
         << "inline constexpr PatternTest kLearnedOrbPattern[kPatternTests] = {\n";
      for (const PatternTest& t : learned.tests) {
        os << fmt::format("    {{{}, {}, {}, {}}},\n", t.x1, t.y1, t.x2, t.y2);
      }
      os << "};\n\n}  // namespace dlslam::features\n";
    });
    fmt::print("wrote {}\n", out_path);
  } catch (const dlslam::Error& e) {
    std::cerr << "[error] " << e.what() << "\n";
    return 1;
  }
  return 0;
}
