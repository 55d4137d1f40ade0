// A crowd-sized mask's disc dilation (ours against cv::dilate), a coarse
// mask back at full size (against cv::resize) and its connected components
// (against cv::connectedComponents).
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>

#include "dlslam/image/connected_components.h"
#include "dlslam/image/disc_dilation.h"
#include "dlslam/image/upsample.h"

namespace {

// Two people and a table edge: ~40 % of a 640x480 frame, as in a crowd.
cv::Mat CrowdMask() {
  cv::Mat mask = cv::Mat::zeros(480, 640, CV_8UC1);
  cv::ellipse(mask, cv::Point(200, 260), cv::Size(90, 220), 0, 0, 360, 255, -1);
  cv::ellipse(mask, cv::Point(450, 300), cv::Size(120, 200), 0, 0, 360, 255, -1);
  cv::rectangle(mask, cv::Rect(0, 400, 640, 20), 255, -1);
  return mask;
}

void BM_DilateDisc(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat mask = CrowdMask();
  const int radius = static_cast<int>(state.range(0));
  cv::Mat out;
  for (auto _ : state) {
    dlslam::image::DilateDisc(mask, radius, out);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_DilateDisc)->Arg(3)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);

void BM_CvDilateEllipse(benchmark::State& state) {
  cv::setNumThreads(1);
  const cv::Mat mask = CrowdMask();
  const int k = 2 * static_cast<int>(state.range(0)) + 1;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k));
  cv::Mat out;
  for (auto _ : state) {
    cv::dilate(mask, out, kernel);
    benchmark::DoNotOptimize(out.data);
  }
}
BENCHMARK(BM_CvDilateEllipse)->Arg(3)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);

// The free-space check's 4 px cells (arg 4) and region growing's 2 px grid
// (arg 2) back at 640x480.
void BM_UpsampleNearest(benchmark::State& state) {
  const int factor = static_cast<int>(state.range(0));
  cv::Mat grid;
  cv::resize(CrowdMask(), grid, cv::Size(640 / factor, 480 / factor), 0, 0, cv::INTER_NEAREST);
  cv::Mat full;
  for (auto _ : state) {
    dlslam::image::UpsampleNearest(grid, factor, {640, 480}, full);
    benchmark::DoNotOptimize(full.data);
  }
}
BENCHMARK(BM_UpsampleNearest)->Arg(2)->Arg(4)->Unit(benchmark::kMicrosecond);

void BM_CvResizeNearest(benchmark::State& state) {
  cv::setNumThreads(1);
  const int factor = static_cast<int>(state.range(0));
  cv::Mat grid, full;
  cv::resize(CrowdMask(), grid, cv::Size(640 / factor, 480 / factor), 0, 0, cv::INTER_NEAREST);
  for (auto _ : state) {
    cv::resize(grid, full, cv::Size(640, 480), 0, 0, cv::INTER_NEAREST);
    benchmark::DoNotOptimize(full.data);
  }
}
BENCHMARK(BM_CvResizeNearest)->Arg(2)->Arg(4)->Unit(benchmark::kMicrosecond);

// The fusion's segments of a crowd mask: ours against OpenCV's on 1 and 2
// threads of its pool (the system called it on the default, 2 here).
void BM_LabelComponents(benchmark::State& state) {
  const cv::Mat mask = CrowdMask();
  cv::Mat labels;
  for (auto _ : state) benchmark::DoNotOptimize(dlslam::image::LabelComponents(mask, labels));
}
BENCHMARK(BM_LabelComponents)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_CvConnectedComponents(benchmark::State& state) {
  cv::setNumThreads(static_cast<int>(state.range(0)));
  const cv::Mat mask = CrowdMask();
  cv::Mat labels;
  for (auto _ : state) benchmark::DoNotOptimize(cv::connectedComponents(mask, labels, 8, CV_32S));
}
BENCHMARK(BM_CvConnectedComponents)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace
