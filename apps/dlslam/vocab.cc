// dlslam vocab: train and inspect bag-of-words vocabularies (place recognition).
//   dlslam vocab train --images DIR... --out FILE [--k 10] [--levels 5]
//                      [--max-features N] [--max-images N] [--max-side PX] [--seed S] [--threads N]
//   dlslam vocab info [FILE]        (default: the shipped vocabulary)

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli_checks.h"
#include "commands.h"
#include "dlslam/features/orb_extractor.h"
#include "dlslam/io/file_util.h"
#include "dlslam/io/image_io.h"
#include "dlslam/place/vocabulary_file.h"
#include "dlslam/place/vocabulary_training.h"
#include "dlslam/util/check.h"

namespace dlslam::app {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct TrainArgs {
  std::vector<std::string> image_dirs;
  std::string out;
  place::VocabularyOptions options;
  int max_features = features::OrbOptions().n_features;
  int max_images = 0;
  int max_side = 640;
  bool skip_unreadable = false;
};

// `count` paths spread evenly over `files` (all when count is 0 or larger).
std::vector<std::filesystem::path> Spread(const std::vector<std::filesystem::path>& files, int count) {
  if (count <= 0 || static_cast<std::size_t>(count) >= files.size()) return files;
  std::vector<std::filesystem::path> picked;
  for (int i = 0; i < count; ++i) picked.push_back(files[files.size() * static_cast<std::size_t>(i) / count]);
  return picked;
}

// ORB descriptors of every image, extracted on `threads` threads; the result
// does not depend on the thread count (one slot per image).
place::TrainingDescriptors ExtractAll(const std::vector<std::filesystem::path>& images, const TrainArgs& args,
                                      int threads) {
  features::OrbOptions orb_options;
  orb_options.n_features = args.max_features;
  orb_options.Check();
  std::vector<std::vector<Descriptor>> per_image(images.size());
  std::vector<char> skipped(images.size(), 0);
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    features::OrbExtractor extractor(orb_options);
    for (std::size_t i = next++; i < images.size(); i = next++) {
      try {
        cv::Mat image = io::ReadColorImage({images[i], {}, 0}, 0, 0);
        const int side = std::max(image.cols, image.rows);
        if (args.max_side > 0 && side > args.max_side) {
          const double scale = static_cast<double>(args.max_side) / side;
          cv::resize(image, image, cv::Size(), scale, scale, cv::INTER_AREA);
        }
        per_image[i] = place::DescriptorsFromMat(extractor.Extract(image).descriptors);
      } catch (const InputError& e) {
        if (args.skip_unreadable) {
          skipped[i] = 1;
          spdlog::warn("skipped: {}", e.what());
        } else {
          std::lock_guard lock(failure_mutex);
          if (!failure) failure = std::current_exception();
          next = images.size();
        }
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = images.size();
      }
      const std::size_t finished = ++done;
      if (finished % 200 == 0) spdlog::info("features: {} / {} images", finished, images.size());
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  place::TrainingDescriptors training;
  std::size_t skipped_count = 0;
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (skipped[i]) {
      ++skipped_count;
    } else {
      training.AddImage(per_image[i]);
    }
  }
  if (skipped_count > 0) spdlog::warn("{} of {} files skipped (not readable as 8-bit colour)", skipped_count, images.size());
  return training;
}

void RunTrain(const TrainArgs& args) {
  args.options.Check();
  DLSLAM_CHECK_GT(args.max_features, 0, "--max-features must be positive");
  DLSLAM_CHECK_GE(args.max_side, 0, "--max-side must be >= 0 (0 = keep the size)");
  std::vector<std::filesystem::path> files;
  for (const std::string& dir : args.image_dirs) {
    const auto found = io::FindFilesRecursively(dir, {".png", ".jpg", ".jpeg"});
    spdlog::info("{}: {} images", dir, found.size());
    files.insert(files.end(), found.begin(), found.end());
  }
  if (files.empty()) throw Error("vocab train: no .png/.jpg images under the --images folders");
  files = Spread(files, args.max_images);
  const int threads = args.options.threads > 0 ? args.options.threads
                                               : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));

  const auto extract_start = Clock::now();
  const place::TrainingDescriptors training = ExtractAll(files, args, threads);
  spdlog::info("features: {} descriptors from {} images in {:.1f} s", training.descriptors.size(),
               training.image_count(), SecondsSince(extract_start));

  const auto train_start = Clock::now();
  const place::Vocabulary vocabulary = place::TrainVocabulary(training, args.options);
  spdlog::info("tree: k {} levels {}: {} nodes, {} words in {:.1f} s", vocabulary.branching(),
               vocabulary.levels(), vocabulary.node_count(), vocabulary.word_count(), SecondsSince(train_start));
  place::SaveVocabulary(vocabulary, args.out, {training.image_count(), training.descriptors.size()});
  fmt::print("wrote {} ({:.2f} MB): k {}, levels {}, {} words, from {} descriptors of {} images\n", args.out,
             static_cast<double>(std::filesystem::file_size(args.out)) / 1e6, vocabulary.branching(),
             vocabulary.levels(), vocabulary.word_count(), training.descriptors.size(), training.image_count());
}

void RunInfo(const std::string& file) {
  const std::filesystem::path path = place::FindVocabulary(file);
  constexpr int kLoads = 5;
  std::vector<double> milliseconds;
  place::Vocabulary vocabulary;
  place::TrainingSummary summary;
  for (int i = 0; i < kLoads; ++i) {
    const auto start = Clock::now();
    vocabulary = place::LoadVocabulary(path, &summary);
    milliseconds.push_back(1e3 * SecondsSince(start));
  }
  const double first = milliseconds.front();
  std::sort(milliseconds.begin(), milliseconds.end());
  std::size_t deepest_leaves = 0;
  for (std::size_t node = 0; node < vocabulary.node_count(); ++node) {
    if (vocabulary.child_counts()[node] == 0 && vocabulary.depth_of_node(static_cast<place::NodeId>(node)) ==
                                                    vocabulary.levels()) {
      ++deepest_leaves;
    }
  }
  fmt::print("file          {}\n", path.string());
  fmt::print("size          {} bytes ({:.2f} MB)\n", std::filesystem::file_size(path),
             static_cast<double>(std::filesystem::file_size(path)) / 1e6);
  fmt::print("tree          k {}, levels {}, {} nodes\n", vocabulary.branching(), vocabulary.levels(),
             vocabulary.node_count());
  fmt::print("words         {} (of at most {:.0f}; {} at the last level)\n", vocabulary.word_count(),
             std::pow(vocabulary.branching(), vocabulary.levels()), deepest_leaves);
  fmt::print("weighting     tf-idf, L1 score\n");
  fmt::print("trained on    {} descriptors of {} images\n", summary.descriptors, summary.images);
  fmt::print("load time     {:.1f} ms first, {:.1f} ms median of {} (read + checksum + tree)\n", first,
             milliseconds[kLoads / 2], kLoads);
}

}  // namespace

void AddVocabCommand(CLI::App& app) {
  CLI::App* vocab = app.add_subcommand("vocab", "Bag-of-words vocabularies for place recognition: train, info");
  vocab->require_subcommand(1);

  auto train_args = std::make_shared<TrainArgs>();
  CLI::App* train = vocab->add_subcommand("train", "Train a vocabulary tree from the ORB features of images");
  train->add_option("--images", train_args->image_dirs, "Folders searched recursively for .png/.jpg images")
      ->required()
      ->check(CLI::ExistingDirectory);
  train->add_option("--out", train_args->out, "Vocabulary file to write (.dlv)")->required();
  train->add_option("--k", train_args->options.branching, "Branching factor")->capture_default_str()->check(WholeNumber(2, 255));
  train->add_option("--levels", train_args->options.levels, "Tree levels below the root")->capture_default_str()->check(WholeNumber(1, 16));
  train->add_option("--max-features", train_args->max_features, "ORB features per image")->capture_default_str()->check(WholeNumber(1, 100000));
  train->add_option("--max-images", train_args->max_images, "Use at most N images, spread over the list (0 = all)")
      ->capture_default_str()->check(WholeNumber(0, 1000000000));
  train->add_option("--max-side", train_args->max_side,
                    "Shrink larger images to this longer side first [px] (0 = keep)")
      ->capture_default_str()->check(WholeNumber(0, 100000));
  train->add_flag("--skip-unreadable", train_args->skip_unreadable,
                  "Skip files that are not 8-bit colour images (e.g. 16-bit depth) with a warning, instead of failing");
  train->add_option("--iterations", train_args->options.max_iterations, "k-means iterations per node, at most")
      ->capture_default_str()->check(WholeNumber(1, 10000));
  train->add_option("--seed", train_args->options.seed, "Seed (same seed and images: same file)")
      ->capture_default_str()->check(WholeNumber(0, 9223372036854775807));
  train->add_option("--threads", train_args->options.threads, "Threads (0 = all cores)")->capture_default_str()->check(WholeNumber(0, place::kMaxVocabularyThreads));
  train->callback([train_args] { RunTrain(*train_args); });

  auto info_file = std::make_shared<std::string>();
  CLI::App* info = vocab->add_subcommand("info", "Print a vocabulary's parameters, size and load time");
  info->add_option("file", *info_file, "Vocabulary file (default: the shipped one)");
  info->callback([info_file] { RunInfo(*info_file); });
}

}  // namespace dlslam::app
