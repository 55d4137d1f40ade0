// Our ORB against cv::ORB (OpenCV 4.6) with the same n_features / levels /
// scale on a real 640x480 frame (7-Scenes redkitchen from the shared data,
// else a synthetic texture), and our FAST grid against cv::FAST:
//
//   build/bin/dlslam_bench_features --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
//
// The argument is OpenCV's thread count: 1, or 0 for its default.

#include <benchmark/benchmark.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "dlslam/features/fast_detector.h"
#include "dlslam/features/matching.h"
#include "dlslam/features/orb_extractor.h"

namespace dlslam::features {
namespace {

bool real_image = false;

const cv::Mat& BenchImage() {
  static const cv::Mat image = [] {
    std::filesystem::path root = std::filesystem::path(DLSLAM_SOURCE_DIR).parent_path() / "shared" / "data";
    if (const char* env = std::getenv("DLSLAM_SHARED_DATA"); env && *env) root = env;
    const auto path = root / "7scenes-redkitchen-500" / "rgb" / "0.000000.jpg";
    cv::Mat grey = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    real_image = !grey.empty();
    if (real_image) return grey;
    // Fallback: smoothed noise with blocks, textured everywhere.
    cv::Mat synthetic(480, 640, CV_8UC1);
    cv::randu(synthetic, 0, 256);
    cv::resize(synthetic(cv::Rect(0, 0, 80, 60)), synthetic, synthetic.size(), 0, 0, cv::INTER_NEAREST);
    cv::GaussianBlur(synthetic, synthetic, cv::Size(5, 5), 1.0);
    return synthetic;
  }();
  return image;
}

void SetThreads(const benchmark::State& state) {
  cv::setNumThreads(state.range(0) == 0 ? -1 : static_cast<int>(state.range(0)));
}

void AddContext(benchmark::State& state, size_t keypoints) {
  state.counters["keypoints"] = static_cast<double>(keypoints);
  state.SetLabel(real_image ? "7scenes 640x480" : "synthetic 640x480");
}

void BM_OursExtract(benchmark::State& state) {
  SetThreads(state);
  OrbExtractor orb;
  OrbFeatures features;
  for (auto _ : state) {
    orb.Extract(BenchImage(), cv::Mat(), features);
    benchmark::DoNotOptimize(features.descriptors.data);
  }
  AddContext(state, features.keypoints.size());
}
BENCHMARK(BM_OursExtract)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// As the system extracts again outside the removed regions in a crowd: the
// static extractor's lower FAST thresholds (8 / 4), people as two upright
// bands over 40 % of the image (argument: OpenCV threads).
void BM_OursExtractOutsideMask(benchmark::State& state) {
  SetThreads(state);
  OrbOptions options;
  options.fast_threshold_initial = 8;
  options.fast_threshold_min = 4;
  OrbExtractor orb(options);
  cv::Mat people(BenchImage().size(), CV_8UC1, cv::Scalar(0));
  people(cv::Rect(100, 60, 128, 420)).setTo(255);
  people(cv::Rect(380, 40, 128, 440)).setTo(255);
  OrbFeatures features;
  for (auto _ : state) {
    orb.Extract(BenchImage(), people, features);
    benchmark::DoNotOptimize(features.descriptors.data);
  }
  AddContext(state, features.keypoints.size());
}
BENCHMARK(BM_OursExtractOutsideMask)->Arg(1)->Unit(benchmark::kMillisecond);

// The system's second extraction of a crowded frame after the dynamic stage
// grew the removal, on the first one's pyramid (timed: the second alone):
// /0 Reextract, the first extraction outside the network's people with the
// static thresholds (mode full); /1 ExtractOn, the first extraction of the
// whole image with the default thresholds (mode geometry). Either reuses the
// descriptors of the corners the first one described.
void BM_SecondExtraction(benchmark::State& state) {
  OrbOptions low;
  low.fast_threshold_initial = 8;
  low.fast_threshold_min = 4;
  OrbExtractor first_default, statics(low);
  cv::Mat people(BenchImage().size(), CV_8UC1, cv::Scalar(0));
  people(cv::Rect(100, 60, 128, 420)).setTo(255);
  cv::Mat grown = people.clone();
  people(cv::Rect(380, 40, 128, 440)).setTo(255);  // a second person only geometry found
  grown(cv::Rect(90, 50, 148, 430)).setTo(255);     // and the fusion's margin
  grown(cv::Rect(370, 30, 148, 450)).setTo(255);
  const bool full_mode = state.range(0) == 0;
  OrbFeatures features;
  for (auto _ : state) {
    state.PauseTiming();
    if (full_mode) {
      statics.Extract(BenchImage(), people, features);
    } else {
      first_default.Extract(BenchImage(), cv::Mat(), features);
    }
    state.ResumeTiming();
    features = full_mode ? statics.Reextract(grown) : statics.ExtractOn(first_default, grown);
    benchmark::DoNotOptimize(features.descriptors.data);
  }
  AddContext(state, features.keypoints.size());
}
BENCHMARK(BM_SecondExtraction)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void CvOrb(benchmark::State& state, cv::ORB::ScoreType score) {
  SetThreads(state);
  const auto orb = cv::ORB::create(1000, 1.2f, 8, 31, 0, 2, score, 31, 20);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  for (auto _ : state) {
    orb->detectAndCompute(BenchImage(), cv::noArray(), keypoints, descriptors);
    benchmark::DoNotOptimize(descriptors.data);
  }
  AddContext(state, keypoints.size());
}
void BM_CvOrbHarris(benchmark::State& state) { CvOrb(state, cv::ORB::HARRIS_SCORE); }
void BM_CvOrbFastScore(benchmark::State& state) { CvOrb(state, cv::ORB::FAST_SCORE); }
BENCHMARK(BM_CvOrbHarris)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CvOrbFastScore)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// FAST on the full-resolution level, as the extractor runs it: our grid with
// the fallback threshold, against cv::FAST called per cell (ORB-SLAM's way)
// and cv::FAST once on the whole image at the initial threshold only.
const cv::Rect kArea(19, 19, 640 - 38, 480 - 38);

void BM_OursFastGrid(benchmark::State& state) {
  SetThreads(state);
  FastScratch scratch;
  std::vector<FastCorner> corners;
  for (auto _ : state) {
    corners.clear();
    DetectGridFast(BenchImage(), kArea, {20, 7, 30}, scratch, corners);
    benchmark::DoNotOptimize(corners.data());
  }
  AddContext(state, corners.size());
}
BENCHMARK(BM_OursFastGrid)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_CvFastPerCell(benchmark::State& state) {
  SetThreads(state);
  std::vector<cv::KeyPoint> cell_keypoints;
  size_t n = 0;
  for (auto _ : state) {
    n = 0;
    for (int y = kArea.y; y < kArea.br().y; y += 30) {
      for (int x = kArea.x; x < kArea.br().x; x += 30) {
        // The cell plus the 3 px FAST reads around it.
        const cv::Rect cell = cv::Rect(x - 3, y - 3, 36, 36) & cv::Rect(16, 16, 640 - 32, 480 - 32);
        cv::FAST(BenchImage()(cell), cell_keypoints, 20, true);
        if (cell_keypoints.empty()) cv::FAST(BenchImage()(cell), cell_keypoints, 7, true);
        n += cell_keypoints.size();
      }
    }
    benchmark::DoNotOptimize(n);
  }
  AddContext(state, n);
}
BENCHMARK(BM_CvFastPerCell)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_CvFastWholeImage(benchmark::State& state) {
  SetThreads(state);
  std::vector<cv::KeyPoint> keypoints;
  for (auto _ : state) {
    cv::FAST(BenchImage()(kArea), keypoints, 20, true);
    benchmark::DoNotOptimize(keypoints.data());
  }
  AddContext(state, keypoints.size());
}
BENCHMARK(BM_CvFastWholeImage)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_MatchBruteForce1000(benchmark::State& state) {
  SetThreads(state);
  OrbExtractor orb;
  const OrbFeatures f = orb.Extract(BenchImage());
  cv::Mat turned;
  cv::rotate(BenchImage(), turned, cv::ROTATE_90_CLOCKWISE);
  const OrbFeatures g = orb.Extract(turned);
  size_t n = 0;
  for (auto _ : state) {
    n = MatchBruteForce(f.descriptors, g.descriptors).size();
    benchmark::DoNotOptimize(n);
  }
  state.counters["matches"] = static_cast<double>(n);
}
BENCHMARK(BM_MatchBruteForce1000)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dlslam::features
