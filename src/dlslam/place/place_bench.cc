// Place recognition speed: vocabulary load, Transform of a 1000-feature
// frame, database queries with 500 keyframes; and, as counters, the
// revisit precision on redkitchen (or another sequence). Uses the shipped vocabulary, or
// $DLSLAM_VOCABULARY; real frames from shared data when present.
//   build/bin/dlslam_bench_place --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <random>

#include "dlslam/features/orb_extractor.h"
#include "dlslam/io/image_io.h"
#include "dlslam/place/keyframe_database.h"
#include "dlslam/place/place_candidates.h"
#include "dlslam/place/test_sequences.h"
#include "dlslam/place/vocabulary_file.h"

namespace dlslam::place {
namespace {

std::filesystem::path VocabularyPath() {
  const char* env = std::getenv("DLSLAM_VOCABULARY");
  return FindVocabulary(env != nullptr ? env : "");
}

const Vocabulary& TheVocabulary() {
  static const Vocabulary vocabulary = LoadVocabulary(VocabularyPath());
  return vocabulary;
}

std::filesystem::path SharedData() {
  const char* env = std::getenv("DLSLAM_SHARED_DATA");
  return env != nullptr ? std::filesystem::path(env) : std::filesystem::path(DLSLAM_SOURCE_DIR) / ".." / "shared" / "data";
}

// Descriptors of real 640x480 frames when shared data is there, else of
// synthetic ones.
std::vector<std::vector<Descriptor>> Frames(int count) {
  static std::vector<std::vector<Descriptor>> frames;
  if (static_cast<int>(frames.size()) >= count) return {frames.begin(), frames.begin() + count};
  features::OrbExtractor extractor;
  const auto dir = SharedData() / "7scenes-redkitchen-500" / "rgb";
  if (std::filesystem::is_directory(dir)) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (int i = static_cast<int>(frames.size()); i < count; ++i) {
      const cv::Mat image = io::ReadColorImage({files[static_cast<std::size_t>(i) % files.size()], {}, 0}, 0, 0);
      frames.push_back(DescriptorsFromMat(extractor.Extract(image).descriptors));
    }
  } else {
    const synth::Scene scene = synth::BuildScene(synth::Preset::kStatic, 1);
    for (int i = static_cast<int>(frames.size()); i < count; ++i) {
      const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitY()));
      const cv::Mat image = testing::RenderColour(scene, scene.viewpoint * SE3d(turn, Eigen::Vector3d::Zero()), static_cast<std::uint32_t>(i));
      frames.push_back(DescriptorsFromMat(extractor.Extract(image).descriptors));
    }
  }
  return frames;
}

void BM_LoadVocabulary(benchmark::State& state) {
  const auto path = VocabularyPath();
  for (auto _ : state) benchmark::DoNotOptimize(LoadVocabulary(path));
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  state.counters["words"] = static_cast<double>(TheVocabulary().word_count());
}
BENCHMARK(BM_LoadVocabulary)->Unit(benchmark::kMillisecond);

void BM_Transform(benchmark::State& state) {
  const auto frame = Frames(1)[0];
  BowVector bow;
  FeatureVector features;
  for (auto _ : state) {
    TheVocabulary().Transform(frame, 2, bow, features);
    benchmark::DoNotOptimize(bow.data());
  }
  state.counters["features"] = static_cast<double>(frame.size());
  state.counters["words"] = static_cast<double>(bow.size());
}
BENCHMARK(BM_Transform)->Unit(benchmark::kMillisecond);

// 500 keyframes (real frames when available, repeating after 500), queried
// with one of them; neighbours = the 10 frames around each keyframe.
void BM_QueryRelocalization(benchmark::State& state) {
  constexpr int kKeyFrames = 500;
  const auto frames = Frames(kKeyFrames);
  KeyFrameDatabase database(TheVocabulary().word_count());
  std::vector<BowVector> bows;
  for (int i = 0; i < kKeyFrames; ++i) {
    bows.push_back(TheVocabulary().Transform(frames[static_cast<std::size_t>(i)]));
    database.Add(static_cast<KeyFrameId>(i), bows.back());
  }
  const CovisibleNeighbours neighbours = [](KeyFrameId id, int count) {
    std::vector<KeyFrameId> out;
    for (int d = 1; static_cast<int>(out.size()) < count && d <= 5; ++d) {
      if (id >= static_cast<KeyFrameId>(d)) out.push_back(id - static_cast<KeyFrameId>(d));
      if (id + static_cast<KeyFrameId>(d) < kKeyFrames) out.push_back(id + static_cast<KeyFrameId>(d));
    }
    return out;
  };
  std::size_t query = 0;
  std::size_t candidates = 0;
  for (auto _ : state) {
    const auto found = DetectRelocalizationCandidates(database, bows[query], neighbours);
    candidates += found.size();
    query = (query + 37) % bows.size();
  }
  state.counters["keyframes"] = kKeyFrames;
  state.counters["candidates"] = static_cast<double>(candidates) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_QueryRelocalization)->Unit(benchmark::kMillisecond);

// Not a speed: precision@1 of revisits (revisit_evaluation.h) on every frame
// of redkitchen, or of the TUM-layout folder $DLSLAM_REVISIT_SEQUENCE (e.g.
// a `dlslam synth` sequence), as counters.
void BM_Revisits(benchmark::State& state) {
  const char* env = std::getenv("DLSLAM_REVISIT_SEQUENCE");
  const auto dir = env != nullptr ? std::filesystem::path(env) : SharedData() / "7scenes-redkitchen-500";
  if (!std::filesystem::is_directory(dir)) {
    state.SkipWithError("sequence folder not found (shared data 7scenes-redkitchen-500)");
    return;
  }
  RevisitEvaluation result, strict;
  for (auto _ : state) {
    const auto frames = testing::LoadRevisitFrames(dir, 1, TheVocabulary());
    result = EvaluateRevisits(frames);
    strict = EvaluateRevisits(frames, {100, 0.3, 20.0, 0.3, 20.0});
  }
  state.counters["queries"] = result.queries;
  state.counters["precision_at_1"] = result.precision_at_1;
  state.counters["chance"] = result.chance;
  state.counters["correct"] = result.correct;
  state.counters["strict_precision_at_1"] = strict.precision_at_1;
  state.counters["strict_chance"] = strict.chance;
}
BENCHMARK(BM_Revisits)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace dlslam::place
