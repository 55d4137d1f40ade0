#pragma once
// The semantic thread's per-frame segmentation: which pixels belong to
// a-priori dynamic objects (people) and to movable ones (chairs). A Segmenter
// is one backend (OpenCV dnn on an ONNX model today); SegmentationWorker runs
// one in its own thread.
//
//   auto segmenter = MakeSegmenter(SegmenterOptions{});   // shipped model, resolved
//   SegmentationResult r = segmenter->Segment(bgr);      // r.dynamic_mask: 0 / 255

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace dlslam::semantic {

// The shipped model (models/README.md): 0 background, 1 person, 2 chair.
inline constexpr const char* kDefaultModelFile = "dlslam_seg_mnv2_w05_209x273.onnx";

struct SegmenterOptions {
  // Backend: "opencv-dnn" (ONNX through cv::dnn, CPU). The only one so far.
  std::string backend = "opencv-dnn";
  // ONNX model file; "" = kDefaultModelFile found by io::FindModelFile
  // ($DLSLAM_MODEL_DIR, <exe>/../share/dlslam/models, the source tree's models/).
  std::filesystem::path model_path;
  // Network input [px]; 0 x 0 = the fixed size the model file declares
  // (semantic/onnx_shape.h), so a model exported at another size needs no
  // option beside it. The shipped model declares 209x273 (trained at 257x337,
  // exported smaller for speed: docs/semantic.md, "Input size"). After
  // loading, a segmenter's options() hold the size it runs at.
  int input_width = 0;
  int input_height = 0;
  // Output channels (classes) the model must have; checked by a dry forward at load.
  int num_classes = 3;
  // Class ids removed from SLAM in every frame (default: person).
  std::vector<int> dynamic_classes = {1};
  // Class ids that are static until a person moves them (default: chair).
  std::vector<int> movable_classes = {2};
  // Growth of the dynamic mask [px, frame resolution] by an elliptic
  // dilation: covers the boundary pixels the network misses (hair, motion
  // blur) and keypoints whose patch straddles the person's outline. 0 = none.
  int dynamic_margin_px = 5;
  // OpenCV's thread count for inference (cv::setNumThreads, which is
  // process-wide: ORB extraction's parallel loops share it); 0 = leave as is.
  int threads = 0;
  // Smallest frame side accepted by Segment() [px]: smaller images carry no
  // information at the network's stride of 16 and are a caller's mistake.
  int min_image_side = 16;

  // Throws dlslam::Error naming the bad value.
  void Check() const;
};

struct SegmentationResult {
  // Class id per pixel, CV_8UC1 at the frame size.
  cv::Mat labels;
  // 255 = a-priori dynamic (dilated by the margin, and more when propagated),
  // 0 = not; CV_8UC1 at the frame size.
  cv::Mat dynamic_mask;
  // 255 = movable class (not dilated), 0 = not; CV_8UC1 at the frame size.
  cv::Mat movable_mask;
  // Frames since the frame that was actually segmented: 0 = this frame;
  // k > 0 = masks propagated from k frames earlier (SegmentationWorker).
  int propagated_from = 0;
  // Wall time of the Segment() call [s]; 0 for a propagated result.
  double seconds = 0.0;
};

// One segmentation backend. Not thread-safe: one instance per thread (the
// worker owns its own). Results share no memory with the input frame.
class Segmenter {
 public:
  virtual ~Segmenter() = default;
  // bgr: CV_8UC3, any size >= min_image_side. Throws dlslam::Error for an
  // empty image, another type or a too small one.
  virtual SegmentationResult Segment(const cv::Mat& bgr) = 0;
  virtual const SegmenterOptions& options() const = 0;
};

// The backend named by options.backend, model loaded and checked. Throws
// InputError naming the model file if it is missing, corrupt or has the wrong
// output shape; dlslam::Error for bad options.
std::unique_ptr<Segmenter> MakeSegmenter(const SegmenterOptions& options);

}  // namespace dlslam::semantic
