// Accuracy / time trade-off of segmenting every k-th frame and propagating
// the last mask (grown by `grow` px per frame) to the frames in between, as
// SegmentationWorker does, on a video with ground-truth person masks:
//
//   nice -n 10 build/bin/segment_propagation_eval
//     --images ../shared/data/segmentation/davis-parkour/images
//     --masks ../shared/data/segmentation/davis-parkour/masks --every 1,2,3,5,10 --grow 0,2,4
//
// Every frame is segmented once (margin --margin px); the rows reuse those
// results through PropagateResult. Time per frame = (segment time of the
// segmented frames + propagation time of the others) / frames, measured here.
// Person IoU / precision / recall of the dynamic mask, pooled over frames.

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "dlslam/semantic/label_maps.h"
#include "dlslam/semantic/segmenter.h"
#include "dlslam/util/check.h"

namespace fs = std::filesystem;
using namespace dlslam::semantic;

namespace {

struct Counts {
  double intersection = 0, predicted = 0, truth = 0;
  void Add(const cv::Mat& predicted_mask, const cv::Mat& truth_mask) {
    intersection += cv::countNonZero(predicted_mask & truth_mask);
    predicted += cv::countNonZero(predicted_mask);
    truth += cv::countNonZero(truth_mask);
  }
  double iou() const { return intersection / (predicted + truth - intersection); }
  double precision() const { return predicted > 0 ? intersection / predicted : 0; }
  double recall() const { return intersection / truth; }
};

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"IoU / time of segmenting every k-th frame with mask propagation"};
  std::string images_dir, masks_dir, model;
  std::vector<int> every = {1, 2, 3, 5, 10}, grow = {0, 2, 4};
  int margin = 0, threads = 0;
  app.add_option("--images", images_dir, "video frames (.jpg / .png, sorted by name)")->required();
  app.add_option("--masks", masks_dir, "ground-truth masks (.png, same stem, >127 = person)")->required();
  app.add_option("--every", every, "segment every k-th frame")->delimiter(',');
  app.add_option("--grow", grow, "growth of a propagated mask [px per frame]")->delimiter(',');
  app.add_option("--margin", margin, "dilation of every dynamic mask [px]");
  app.add_option("--threads", threads, "OpenCV threads (0 = default)");
  app.add_option("--model", model, "ONNX model (default: the shipped one)");
  CLI11_PARSE(app, argc, argv);

  try {
    std::vector<fs::path> frames;
    for (const auto& entry : fs::directory_iterator(images_dir)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".jpg" || ext == ".png") frames.push_back(entry.path());
    }
    std::sort(frames.begin(), frames.end());
    DLSLAM_CHECK(!frames.empty(), "no frames in {}", images_dir);

    SegmenterOptions options;
    options.model_path = model;
    options.dynamic_margin_px = margin;
    options.threads = threads;
    const auto segmenter = MakeSegmenter(options);

    std::vector<SegmentationResult> results;
    std::vector<cv::Mat> truths;
    double segment_seconds = 0;
    for (const fs::path& frame : frames) {
      const cv::Mat bgr = cv::imread(frame.string(), cv::IMREAD_COLOR);
      const fs::path mask_path = fs::path(masks_dir) / frame.filename().replace_extension(".png");
      const cv::Mat truth = cv::imread(mask_path.string(), cv::IMREAD_GRAYSCALE);
      DLSLAM_CHECK(!bgr.empty() && !truth.empty() && truth.size() == bgr.size(), "cannot read {} / {}",
                   frame.string(), mask_path.string());
      results.push_back(segmenter->Segment(bgr));
      segment_seconds += results.back().seconds;
      truths.push_back(truth > 127);
    }
    const double n = static_cast<double>(frames.size());
    fmt::print("{} frames of {}, margin {} px, segment {:.1f} ms per frame (mean)\n\n", frames.size(), images_dir,
               margin, 1e3 * segment_seconds / n);
    fmt::print("| every k | grow [px/frame] | person IoU | precision | recall | ms per frame | segmented |\n");
    fmt::print("|---|---|---|---|---|---|---|\n");
    for (const int k : every) {
      for (const int g : grow) {
        if (k == 1 && g != grow.front()) continue;  // nothing is propagated
        Counts counts;
        double seconds = 0;
        int segmented = 0;
        for (std::size_t i = 0; i < frames.size(); ++i) {
          const std::size_t key = i - i % static_cast<std::size_t>(k);
          if (key == i) {
            counts.Add(results[i].dynamic_mask, truths[i]);
            seconds += results[i].seconds;
            ++segmented;
            continue;
          }
          const auto start = std::chrono::steady_clock::now();
          const SegmentationResult propagated = PropagateResult(results[key], static_cast<int>(i - key), g);
          seconds += Seconds(start);
          counts.Add(propagated.dynamic_mask, truths[i]);
        }
        fmt::print("| {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.1f} | {} |\n", k, k == 1 ? "-" : std::to_string(g),
                   counts.iou(), counts.precision(), counts.recall(), 1e3 * seconds / n, segmented);
      }
    }
  } catch (const dlslam::Error& e) {
    fmt::print(stderr, "[error] {}\n", e.what());
    return 1;
  }
  return 0;
}
