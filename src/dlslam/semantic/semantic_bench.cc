// Segment() on a real 640x480 TUM fr3/walking_xyz frame (people in view; from
// the shared data, else smoothed noise), for the shipped model and the two
// DeepLabv3 VOC teachers (same preprocessing, 21 classes), with 1 and 2
// OpenCV threads; the post-processing alone; and ORB extraction with the
// segmentation one after the other or in the worker thread.
//
//   nice -n 10 build/bin/dlslam_bench_semantic --benchmark_repetitions=5
//     --benchmark_report_aggregates_only=true
//
// The machine is shared: note `uptime`'s load average next to every number.

#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "dlslam/features/orb_extractor.h"
#include "dlslam/io/file_util.h"
#include "dlslam/semantic/label_maps.h"
#include "dlslam/semantic/onnx_segmenter.h"
#include "dlslam/semantic/onnx_shape.h"
#include "dlslam/semantic/segmentation_worker.h"

namespace dlslam::semantic {
namespace {

namespace fs = std::filesystem;

fs::path SharedData() {
  if (const char* env = std::getenv("DLSLAM_SHARED_DATA"); env && *env) return env;
  return fs::path(DLSLAM_SOURCE_DIR).parent_path() / "shared" / "data";
}

bool real_frame = false;

const cv::Mat& BenchFrame() {
  static const cv::Mat frame = [] {
    const fs::path path = SharedData() / "real-samples/tum_walking_xyz_3frames/rgb/1341846313.592026.png";
    cv::Mat bgr = cv::imread(path.string(), cv::IMREAD_COLOR);
    real_frame = !bgr.empty() && bgr.size() == cv::Size(640, 480);
    if (real_frame) return bgr;
    cv::Mat noise(480, 640, CV_8UC3);
    cv::randu(noise, 0, 256);
    cv::GaussianBlur(noise, noise, cv::Size(9, 9), 3.0);
    return noise;
  }();
  return frame;
}

enum Model { kOurs = 0, kTeacherDm05 = 1, kTeacherFull = 2 };

SegmenterOptions OptionsFor(Model model) {
  SegmenterOptions options;
  if (model == kOurs) {
    options.model_path = fs::path(DLSLAM_SOURCE_DIR) / "models" / kDefaultModelFile;
    return options;
  }
  // VOC: 21 classes, person 15, chair 9.
  options.num_classes = 21;
  options.dynamic_classes = {15};
  options.movable_classes = {9};
  const fs::path dir = SharedData() / "models/deeplabv3-mnv2-voc";
  if (model == kTeacherDm05) {
    options.model_path = dir / "deeplabv3_mnv2_dm05_voc_257x337.onnx";
    options.input_width = 337;
    options.input_height = 257;
  } else {
    options.model_path = dir / "deeplabv3_mnv2_voc_385x513.onnx";
    options.input_width = 513;
    options.input_height = 385;
  }
  return options;
}

// One loaded network per model, reused across thread counts.
OnnxSegmenter* SegmenterFor(Model model) {
  static std::map<Model, std::unique_ptr<OnnxSegmenter>> loaded;
  auto& slot = loaded[model];
  if (!slot && fs::exists(OptionsFor(model).model_path)) slot = std::make_unique<OnnxSegmenter>(OptionsFor(model));
  return slot.get();
}

// Args: model, OpenCV threads.
void BM_Segment(benchmark::State& state) {
  const auto model = static_cast<Model>(state.range(0));
  OnnxSegmenter* segmenter = SegmenterFor(model);
  if (segmenter == nullptr) {
    state.SkipWithError("model not found (shared data absent?)");
    return;
  }
  cv::setNumThreads(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(segmenter->Segment(BenchFrame()));
  static const char* kNames[] = {"ours mnv2_w05 209x273", "teacher dm05 257x337", "teacher full 385x513"};
  state.SetLabel(std::string(kNames[model]) + (real_frame ? ", TUM 640x480" : ", synthetic 640x480"));
}
BENCHMARK(BM_Segment)
    ->ArgNames({"model", "threads"})
    ->ArgsProduct({{kOurs, kTeacherDm05, kTeacherFull}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Argmax, class masks, resize to 640x480 and a 5 px dilation (arg: classes),
// at the shipped model's output size.
void BM_Postprocess(benchmark::State& state) {
  cv::setNumThreads(1);
  const int classes = static_cast<int>(state.range(0));
  SegmenterOptions options;
  options.num_classes = classes;
  static const std::optional<DeclaredSize> size = DeclaredInputSize(io::ReadFileBytes(OptionsFor(kOurs).model_path));
  if (!size) {
    state.SkipWithError("the shipped model declares no input size");
    return;
  }
  const int shape[] = {1, classes, size->height, size->width};
  cv::Mat logits(4, shape, CV_32F);
  cv::randn(logits, 0, 3);
  for (auto _ : state) {
    benchmark::DoNotOptimize(ResultFromLabels(ArgmaxLabels(logits), cv::Size(640, 480), options));
  }
}
BENCHMARK(BM_Postprocess)->Arg(3)->Arg(21)->Unit(benchmark::kMicrosecond);

// One tracking step's front end: ORB extraction (1000 features, grey frame)
// and segmentation of the same frame. Arg 0: one after the other in the
// caller; arg 1: segmentation in the SegmentationWorker while the caller
// extracts ORB, then waits for the mask (the paper's Fig. 1). Arg 2: OpenCV
// threads.
void BM_OrbAndSegment(benchmark::State& state) {
  const bool parallel = state.range(0) == 1;
  cv::setNumThreads(static_cast<int>(state.range(1)));
  auto segmenter = std::make_unique<OnnxSegmenter>(OptionsFor(kOurs));
  std::optional<SegmentationWorker> worker;
  if (parallel) worker.emplace(std::move(segmenter));
  features::OrbExtractor orb;
  cv::Mat grey;
  cv::cvtColor(BenchFrame(), grey, cv::COLOR_BGR2GRAY);
  for (auto _ : state) {
    if (parallel) {
      auto mask = worker->Submit(BenchFrame());
      benchmark::DoNotOptimize(orb.Extract(grey));
      benchmark::DoNotOptimize(mask.get());
    } else {
      benchmark::DoNotOptimize(segmenter->Segment(BenchFrame()));
      benchmark::DoNotOptimize(orb.Extract(grey));
    }
  }
  state.SetLabel(parallel ? "worker thread || ORB" : "segment then ORB");
}
BENCHMARK(BM_OrbAndSegment)
    ->ArgNames({"parallel", "threads"})
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace dlslam::semantic
