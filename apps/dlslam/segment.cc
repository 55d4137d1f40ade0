// dlslam segment: masks of a-priori dynamic objects (people) from the
// semantic segmentation network, for one image or a whole sequence.
//   dlslam segment --image IMG [--out mask.png] [--overlay overlay.png] [--model FILE]
//   dlslam segment --sequence DIR --out DIR [--overlay DIR] [--every K]
// Masks are 8-bit PNGs at the input size: 0 background, 255 a-priori dynamic
// (dilated by --margin px).

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <deque>
#include <filesystem>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "cli_checks.h"
#include "commands.h"
#include "dlslam/datasets/progress_bar.h"
#include "dlslam/io/file_util.h"
#include "dlslam/io/image_io.h"
#include "dlslam/io/image_list.h"
#include "dlslam/semantic/segmentation_worker.h"
#include "dlslam/semantic/segmenter.h"
#include "dlslam/util/check.h"

namespace dlslam::app {
namespace {

namespace fs = std::filesystem;

struct SegmentArgs {
  std::string image, sequence, out, overlay, model;
  int margin_px = semantic::SegmenterOptions{}.dynamic_margin_px;
  int threads = 0;
  int every = 1;
  bool quiet = false;
};

// The frame with people tinted red, movable objects blue and the outline of
// the (dilated) dynamic mask in yellow.
cv::Mat Overlay(const cv::Mat& bgr, const semantic::SegmentationResult& r) {
  cv::Mat tinted = bgr.clone();
  tinted.setTo(cv::Scalar(0, 0, 255), (r.labels != 0) & (r.movable_mask == 0));
  tinted.setTo(cv::Scalar(255, 0, 0), r.movable_mask);
  cv::Mat overlay;
  cv::addWeighted(bgr, 0.5, tinted, 0.5, 0.0, overlay);
  std::vector<std::vector<cv::Point>> outlines;
  cv::findContours(r.dynamic_mask.clone(), outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(overlay, outlines, -1, cv::Scalar(0, 255, 255), 2);
  return overlay;
}

double Percent(const cv::Mat& mask) { return 100.0 * cv::countNonZero(mask) / static_cast<double>(mask.total()); }

semantic::SegmenterOptions MakeOptions(const SegmentArgs& args) {
  semantic::SegmenterOptions options;
  options.model_path = args.model;  // "" = found by io::FindModelFile
  options.dynamic_margin_px = args.margin_px;
  options.threads = args.threads;
  return options;
}

void SegmentImage(const SegmentArgs& args) {
  const cv::Mat bgr = io::ReadColorImage({args.image, {}, 0}, 0, 0);
  const auto segmenter = semantic::MakeSegmenter(MakeOptions(args));
  semantic::SegmentationResult r;
  try {
    r = segmenter->Segment(bgr);
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {
    throw InputError(args.image, 0, "{}", e.what());
  }
  if (!args.out.empty()) io::WriteImage(args.out, r.dynamic_mask);
  if (!args.overlay.empty()) io::WriteImage(args.overlay, Overlay(bgr, r));
  fmt::print("{} ({}x{}): {:.1f} ms; dynamic {:.2f} % of pixels (margin {} px), movable {:.2f} %; model {}\n",
             args.image, bgr.cols, bgr.rows, 1e3 * r.seconds, Percent(r.dynamic_mask), args.margin_px,
             Percent(r.movable_mask), segmenter->options().model_path.string());
}

fs::path PrepareFolder(const std::string& dir, const fs::path& rgb_dir) {
  const fs::path path(dir);
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec)) throw InputError(path, 0, "exists and is not a folder");
  fs::create_directories(path, ec);
  if (ec) throw InputError(path, 0, "cannot create folder: {}", ec.message());
  // Masks are named like the colour frames: never write them over those.
  if (fs::exists(rgb_dir, ec) && fs::equivalent(path, rgb_dir, ec)) {
    throw InputError(path, 0, "is the folder of the colour frames; choose another output folder");
  }
  return path;
}

void SegmentSequence(const SegmentArgs& args) {
  DLSLAM_CHECK(!args.out.empty(), "--sequence needs --out DIR for the masks");
  const fs::path folder(args.sequence);
  if (!fs::is_directory(folder)) throw InputError(folder, 0, "sequence folder not found");
  const io::ImageList rgb = io::ReadImageList(folder / "rgb.txt");
  if (rgb.images.empty()) throw InputError(rgb.path, 0, "lists no colour frames");
  const fs::path rgb_dir = (folder / rgb.images.front().path).parent_path();
  const fs::path out = PrepareFolder(args.out, rgb_dir);
  const fs::path overlay_dir = args.overlay.empty() ? fs::path() : PrepareFolder(args.overlay, rgb_dir);

  semantic::SegmentationWorkerOptions worker_options;
  worker_options.segment_every = args.every;
  semantic::SegmentationWorker worker(semantic::MakeSegmenter(MakeOptions(args)), worker_options);

  struct Pending {
    const io::ListedImage* listed;
    cv::Mat bgr;
    std::shared_future<semantic::SegmentationResult> result;
  };
  std::deque<Pending> pending;  // read ahead while the worker segments
  std::vector<std::string> rows;
  double segment_seconds = 0, dynamic_percent = 0;
  int segmented = 0;
  datasets::ProgressBar progress("segment", !args.quiet, "frames");
  const auto finish_one = [&] {
    Pending& p = pending.front();
    semantic::SegmentationResult r;
    try {
      r = p.result.get();
    } catch (const InputError&) {
      throw;
    } catch (const Error& e) {
      throw InputError(p.listed->list_file, p.listed->line, "colour image '{}': {}",
                       (folder / p.listed->path).string(), e.what());
    }
    const fs::path name = p.listed->path.filename().replace_extension(".png");
    io::WriteImage(out / name, r.dynamic_mask);
    if (!overlay_dir.empty()) io::WriteImage(overlay_dir / name, Overlay(p.bgr, r));
    rows.push_back(fmt::format("{:.6f} {}", p.listed->timestamp, name.string()));
    segment_seconds += r.seconds;
    segmented += r.propagated_from == 0;
    dynamic_percent += Percent(r.dynamic_mask);
    pending.pop_front();
    progress.Update(rows.size(), rgb.images.size());
  };
  for (const io::ListedImage& listed : rgb.images) {
    cv::Mat bgr = io::ReadColorImage({folder / listed.path, listed.list_file, listed.line}, 0, 0);
    pending.push_back({&listed, bgr, worker.Submit(bgr)});
    if (pending.size() > 2) finish_one();
  }
  while (!pending.empty()) finish_one();
  progress.Finish();
  worker.Stop();
  io::WriteFileAtomically(out / "mask.txt", [&](std::ostream& os) {
    os << "# dynamic-object masks (0 background, 255 a-priori dynamic) of " << folder.string()
       << "\n# written by dlslam segment\n# timestamp filename\n";
    for (const std::string& row : rows) os << row << '\n';
  });
  fmt::print("{} frames -> {}: {} segmented ({:.1f} ms each), dynamic {:.2f} % of pixels on average\n",
             rows.size(), out.string(), segmented, segmented ? 1e3 * segment_seconds / segmented : 0.0,
             dynamic_percent / static_cast<double>(rows.size()));
}

}  // namespace

void AddSegmentCommand(CLI::App& app) {
  auto args = std::make_shared<SegmentArgs>();
  CLI::App* cmd = app.add_subcommand(
      "segment", "Masks of a-priori dynamic objects (people): 0 background, 255 dynamic, at the input size");
  auto* image = cmd->add_option("--image", args->image, "Colour image (PNG/JPEG) to segment");
  auto* sequence = cmd->add_option("--sequence", args->sequence,
                                   "TUM-layout folder: segments every frame of rgb.txt");
  image->excludes(sequence);
  cmd->add_option("--out", args->out,
                  "Mask PNG (--image), or folder for masks named like the colour frames + mask.txt (--sequence)");
  cmd->add_option("--overlay", args->overlay,
                  "Picture of the segmentation over the image (--image: file; --sequence: folder)");
  cmd->add_option("--model", args->model,
                  "ONNX model (default: the shipped one from $DLSLAM_MODEL_DIR, the install or the source tree)");
  cmd->add_option("--margin", args->margin_px, "Dilation of the dynamic mask [px]")
      ->capture_default_str()
      ->check(WholeNumber(0, 100));
  cmd->add_option("--threads", args->threads, "OpenCV threads (0 = OpenCV's default)")
      ->capture_default_str()
      ->check(WholeNumber(0, 256));
  cmd->add_option("--every", args->every,
                  "--sequence: segment every k-th frame; the frames between reuse the last mask, grown")
      ->capture_default_str()
      ->check(WholeNumber(1, 1000));
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
  cmd->callback([args] {
    if (args->image.empty() == args->sequence.empty()) throw Error("give --image IMG or --sequence DIR");
    if (!args->image.empty()) {
      SegmentImage(*args);
    } else {
      SegmentSequence(*args);
    }
  });
}

}  // namespace dlslam::app
