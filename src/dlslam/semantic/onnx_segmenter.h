#pragma once
// The OpenCV-dnn backend: an ONNX segmentation network with a fixed input
// (models/README.md). Preprocessing as in training: the whole frame resized
// (aspect ratio not kept) to the input size, RGB, (x - 128) / 128.

#include <opencv2/dnn.hpp>

#include <filesystem>
#include <string_view>
#include <vector>

#include "dlslam/semantic/segmenter.h"

namespace dlslam::semantic {

class OnnxSegmenter : public Segmenter {
 public:
  // Reads options.model_path (must be set); an input size of 0 x 0 is the
  // one the file declares. Throws InputError naming the file when it is
  // missing, empty, not a loadable ONNX network, declares no fixed input
  // while the options give none, or when one
  // forward pass on a zero input does not give 1 x num_classes x
  // input_height x input_width.
  explicit OnnxSegmenter(const SegmenterOptions& options);
  // The same from the file's bytes; `model_name` names it in errors.
  OnnxSegmenter(std::string_view model_bytes, const std::filesystem::path& model_name,
                const SegmenterOptions& options);

  SegmentationResult Segment(const cv::Mat& bgr) override;
  const SegmenterOptions& options() const override { return options_; }

  // The network's label map (argmax, network resolution) for a frame; public
  // for tests against the Python reference.
  cv::Mat NetworkLabels(const cv::Mat& bgr);

 private:
  void Load(std::string_view model_bytes);
  cv::Mat Forward(const cv::Mat& blob);
  void CheckFrame(const cv::Mat& bgr) const;

  SegmenterOptions options_;
  std::filesystem::path model_name_;
  cv::dnn::Net net_;
};

}  // namespace dlslam::semantic
