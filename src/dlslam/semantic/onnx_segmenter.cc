#include "dlslam/semantic/onnx_segmenter.h"

#include <fmt/format.h>

#include <fcntl.h>
#include <poll.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <opencv2/core/utility.hpp>
#include <string>

#include "dlslam/io/file_util.h"
#include "dlslam/semantic/label_maps.h"
#include "dlslam/semantic/onnx_shape.h"
#include "dlslam/util/check.h"

namespace dlslam::semantic {

namespace {

// blobFromImage's preprocessing of the shipped model and the VOC teachers.
constexpr double kScale = 1.0 / 128.0;
const cv::Scalar kMean(128, 128, 128);

std::string ShapeText(const cv::Mat& blob) {
  std::string text;
  for (int i = 0; i < blob.dims; ++i) text += (i ? " x " : "") + std::to_string(blob.size[i]);
  return text.empty() ? "empty" : text;
}

// OpenCV's messages span lines and repeat the source path; keep the reason.
std::string OpenCvReason(const cv::Exception& e) { return e.err.empty() ? e.what() : e.err; }

// OpenCV 4.6's ONNX importer is not hardened against corrupt files: some
// byte flips make readNetFromONNX dereference garbage (SIGSEGV) instead of
// throwing. So the import is tried first in a forked child; a child killed
// by a signal (or stuck past kImportTimeoutMs) means the file would crash
// or hang us. Only the single-threaded import runs there: OpenCV's thread
// pool, if the parent started one, does not exist in the child.
// Returns "" when the import ends normally (succeeding or throwing).
std::string ImportCrashReason(std::string_view model_bytes) {
  constexpr int kImportTimeoutMs = 60000;
  const pid_t child = fork();
  if (child < 0) return {};  // cannot probe (no processes left): import as before
  if (child == 0) {
    // Quiet: the crash report (or a sanitizer's) of a file we refuse anyway
    // would only look like one of ours on stderr.
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDERR_FILENO);
    try {
      cv::dnn::readNetFromONNX(model_bytes.data(), model_bytes.size());
    } catch (...) {
    }
    _exit(0);
  }
  const int pidfd = static_cast<int>(syscall(SYS_pidfd_open, child, 0));
  bool ended = true;
  if (pidfd >= 0) {
    pollfd wait{pidfd, POLLIN, 0};
    ended = poll(&wait, 1, kImportTimeoutMs) > 0;
    close(pidfd);
  }
  if (!ended) kill(child, SIGKILL);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (!ended) return fmt::format("OpenCV's ONNX importer did not finish within {} s", kImportTimeoutMs / 1000);
  if (WIFSIGNALED(status)) {
    return fmt::format("OpenCV's ONNX importer crashes on it (signal {})", WTERMSIG(status));
  }
  // The child ends with _exit(0); anything else is a crash that a sanitizer
  // or a handler turned into an exit status.
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return "OpenCV's ONNX importer crashes on it";
  return {};
}

}  // namespace

OnnxSegmenter::OnnxSegmenter(const SegmenterOptions& options)
    : OnnxSegmenter(io::ReadFileBytes(options.model_path), options.model_path, options) {}

OnnxSegmenter::OnnxSegmenter(std::string_view model_bytes, const std::filesystem::path& model_name,
                             const SegmenterOptions& options)
    : options_(options), model_name_(model_name) {
  options_.Check();
  if (options_.threads > 0) cv::setNumThreads(options_.threads);
  Load(model_bytes);
}

void OnnxSegmenter::Load(std::string_view model_bytes) {
  if (model_bytes.empty()) throw InputError(model_name_, 0, "segmentation model file is empty (0 bytes)");
  if (const std::string reason = ImportCrashReason(model_bytes); !reason.empty()) {
    throw InputError(model_name_, 0, "not a loadable ONNX model (corrupt or truncated?): {}", reason);
  }
  try {
    net_ = cv::dnn::readNetFromONNX(reinterpret_cast<const char*>(model_bytes.data()), model_bytes.size());
  } catch (const cv::Exception& e) {
    throw InputError(model_name_, 0, "not a loadable ONNX model (corrupt or truncated?): {}", OpenCvReason(e));
  }
  if (net_.empty()) throw InputError(model_name_, 0, "ONNX model has no layers");
  if (options_.input_width == 0 && options_.input_height == 0) {
    const std::optional<DeclaredSize> declared = DeclaredInputSize(model_bytes);
    if (!declared) {
      throw InputError(model_name_, 0,
                       "ONNX model declares no fixed 1 x 3 x H x W input: give its size "
                       "(semantic.segmenter.input_width / input_height)");
    }
    options_.input_width = declared->width;
    options_.input_height = declared->height;
  }
  net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
  net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);

  // One dry forward pass: a model for another input size, another class
  // count or another task fails here, at load, not on the first frame.
  const int blob_shape[] = {1, 3, options_.input_height, options_.input_width};
  cv::Mat output;
  try {
    output = Forward(cv::Mat(4, blob_shape, CV_32F, cv::Scalar(0)));
  } catch (const cv::Exception& e) {
    throw InputError(model_name_, 0, "ONNX model fails on a 1 x 3 x {} x {} input: {}", options_.input_height,
                     options_.input_width, OpenCvReason(e));
  }
  const bool shape_ok = output.dims == 4 && output.size[0] == 1 && output.size[1] == options_.num_classes &&
                        output.size[2] == options_.input_height && output.size[3] == options_.input_width;
  if (!shape_ok || output.type() != CV_32F) {
    throw InputError(model_name_, 0,
                     "ONNX model output is {} ({}), expected 1 x {} x {} x {} float logits "
                     "(classes x input height x width)",
                     ShapeText(output), output.type() == CV_32F ? "float" : "not float", options_.num_classes,
                     options_.input_height, options_.input_width);
  }
}

cv::Mat OnnxSegmenter::Forward(const cv::Mat& blob) {
  net_.setInput(blob);
  return net_.forward();
}

void OnnxSegmenter::CheckFrame(const cv::Mat& bgr) const {
  // Plain errors, not check failures: a wrong frame is the caller's input.
  if (bgr.empty()) throw Error("empty image given to the segmenter");
  if (bgr.type() != CV_8UC3) {
    throw Error(fmt::format("the segmenter needs an 8-bit BGR image (CV_8UC3), got {} channel(s) of {}-bit",
                            bgr.channels(), bgr.elemSize1() * 8));
  }
  if (bgr.dims != 2 || bgr.cols < options_.min_image_side || bgr.rows < options_.min_image_side) {
    throw Error(fmt::format("image of {}x{} px is smaller than {} px on a side", bgr.cols, bgr.rows,
                            options_.min_image_side));
  }
}

cv::Mat OnnxSegmenter::NetworkLabels(const cv::Mat& bgr) {
  CheckFrame(bgr);
  const cv::Mat blob = cv::dnn::blobFromImage(bgr, kScale, cv::Size(options_.input_width, options_.input_height),
                                              kMean, /*swapRB=*/true, /*crop=*/false);
  return ArgmaxLabels(Forward(blob));
}

SegmentationResult OnnxSegmenter::Segment(const cv::Mat& bgr) {
  const auto start = std::chrono::steady_clock::now();
  SegmentationResult result = ResultFromLabels(NetworkLabels(bgr), bgr.size(), options_);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace dlslam::semantic
