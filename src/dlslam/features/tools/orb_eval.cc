// Repeatability and matching precision / recall of our ORB against cv::ORB
// (HARRIS_SCORE and FAST_SCORE, same n_features / levels / scale) on real
// images turned and scaled by known transforms:
//
//   build/bin/orb_eval --images ../shared/data/7scenes-redkitchen-500/rgb --every 25
//
// Prints one table row per transform and extractor (pooled over the images).
// Besides ours and cv::ORB, two rows separate detector from descriptor:
// "ours-no-fallback" (fast_threshold_min = fast_threshold_initial, no weak
// corners from the fallback threshold) and "cv-kp+our-desc" (cv::ORB's
// keypoints and angles described with our steered BRIEF and pattern).

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "dlslam/features/evaluation.h"
#include "dlslam/features/orb_extractor.h"
#include "dlslam/util/check.h"

namespace fs = std::filesystem;
using namespace dlslam::features;

namespace {

struct Transform {
  double angle_deg, scale;
  std::string name() const {
    return scale == 1.0 ? fmt::format("rotate {:g}", angle_deg) : fmt::format("scale {:g}", scale);
  }
};

TransformScores& operator+=(TransformScores& a, const TransformScores& b) {
  a.keypoints_a += b.keypoints_a;
  a.keypoints_b += b.keypoints_b;
  a.repeated += b.repeated;
  a.repeated_by_chance += b.repeated_by_chance;
  a.matches += b.matches;
  a.correct_matches += b.correct_matches;
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Compare our ORB with cv::ORB under known rotations and scales"};
  std::string images_dir, pattern_name = "learned";
  int every = 25;
  double tolerance = 3.0;
  app.add_option("--images", images_dir, "folder of .jpg / .png images")->required();
  app.add_option("--every", every, "use every n-th image")->check(CLI::PositiveNumber);
  app.add_option("--tolerance", tolerance, "correspondence tolerance [px]");
  app.add_option("--pattern", pattern_name, "our test pattern: learned | uniform | gaussian")
      ->check(CLI::IsMember({"learned", "uniform", "gaussian"}));
  CLI11_PARSE(app, argc, argv);

  try {
    if (!fs::is_directory(images_dir)) throw dlslam::InputError(images_dir, 0, "not a folder");
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(images_dir)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".jpg" || ext == ".png") files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());

    std::vector<PatternTest> pattern(LearnedOrbPattern().begin(), LearnedOrbPattern().end());
    if (pattern_name == "uniform") pattern = RandomOrbPattern(RandomPatternKind::kUniform, 1);
    if (pattern_name == "gaussian") pattern = RandomOrbPattern(RandomPatternKind::kGaussian, 1);
    OrbExtractor ours(OrbOptions{}, pattern);
    OrbOptions no_fallback_options;
    no_fallback_options.fast_threshold_min = no_fallback_options.fast_threshold_initial;
    OrbExtractor ours_no_fallback(no_fallback_options, pattern);
    const auto cv_harris = cv::ORB::create(1000, 1.2f, 8, 31, 0, 2, cv::ORB::HARRIS_SCORE);
    const auto cv_fast = cv::ORB::create(1000, 1.2f, 8, 31, 0, 2, cv::ORB::FAST_SCORE);
    const auto extract = [&](const std::string& who, const cv::Mat& image) {
      Features f;
      if (who == "ours" || who == "ours-no-fallback") {
        OrbFeatures o = (who == "ours" ? ours : ours_no_fallback).Extract(image);
        f.keypoints = std::move(o.keypoints);
        f.descriptors = o.descriptors;
      } else if (who == "cv-kp+our-desc") {
        // Our pyramid has cv::ORB's level sizes (round(size / 1.2^level)).
        std::vector<cv::KeyPoint> keypoints;
        cv::Mat unused;
        cv_harris->detectAndCompute(image, cv::noArray(), keypoints, unused);
        OrbFeatures o = ours.Describe(image, keypoints);
        f.keypoints = std::move(o.keypoints);
        f.descriptors = o.descriptors;
      } else {
        (who == "cv-harris" ? cv_harris : cv_fast)->detectAndCompute(image, cv::noArray(), f.keypoints,
                                                                    f.descriptors);
      }
      return f;
    };

    const std::vector<Transform> transforms = {{30, 1.0}, {60, 1.0}, {90, 1.0}, {0, 0.8}, {0, 1.25}};
    const std::vector<std::string> extractors = {"ours", "ours-no-fallback", "cv-harris", "cv-fast",
                                                 "cv-kp+our-desc"};
    long weak = 0, total_ours = 0;  // our keypoints below the initial FAST threshold
    std::map<std::pair<std::string, std::string>, TransformScores> totals;
    int n_images = 0;
    for (size_t i = 0; i < files.size(); i += static_cast<size_t>(every)) {
      const cv::Mat image = cv::imread(files[i].string(), cv::IMREAD_GRAYSCALE);
      if (image.empty()) throw dlslam::InputError(files[i], 0, "cannot read the image");
      ++n_images;
      for (const cv::KeyPoint& k : ours.Extract(image).keypoints) {
        weak += k.response < static_cast<float>(ours.options().fast_threshold_initial);
        ++total_ours;
      }
      for (const Transform& t : transforms) {
        const WarpedImage warped = WarpImage(image, t.angle_deg, t.scale);
        for (const std::string& who : extractors) {
          totals[{t.name(), who}] += ScoreUnderTransform(extract(who, image), extract(who, warped.image),
                                                         warped, tolerance);
        }
      }
    }
    fmt::print("{} images from {}, tolerance {} px, our pattern: {}\n", n_images, images_dir,
               tolerance, pattern_name);
    fmt::print("ours: {:.1f}% of the keypoints come from the fallback threshold\n",
               100.0 * static_cast<double>(weak) / static_cast<double>(std::max(1L, total_ours)));
    fmt::print("| transform | extractor | repeatability (by chance) | precision | recall | matches/image |\n");
    fmt::print("|---|---|---|---|---|---|\n");
    for (const Transform& t : transforms) {
      for (const std::string& who : extractors) {
        const TransformScores& s = totals[{t.name(), who}];
        fmt::print("| {} | {} | {:.3f} ({:.3f}) | {:.3f} | {:.3f} | {:.0f} |\n", t.name(), who,
                   s.repeatability(), s.chance_repeatability(), s.precision(), s.recall(),
                   static_cast<double>(s.matches) / n_images);
      }
    }
  } catch (const dlslam::Error& e) {
    std::cerr << "[error] " << e.what() << "\n";
    return 1;
  }
  return 0;
}
