#include "dlslam/semantic/segmenter.h"

#include <fmt/ranges.h>

#include <algorithm>

#include "dlslam/io/model_file.h"
#include "dlslam/semantic/onnx_segmenter.h"
#include "dlslam/util/check.h"

namespace dlslam::semantic {

void SegmenterOptions::Check() const {
  DLSLAM_CHECK(backend == "opencv-dnn", "unknown segmentation backend '{}' (known: opencv-dnn)", backend);
  DLSLAM_CHECK((input_width == 0 && input_height == 0) || (input_width > 0 && input_height > 0),
               "network input size {}x{} [px] must be positive, or 0x0 for the model's own", input_width,
               input_height);
  DLSLAM_CHECK(num_classes >= 1 && num_classes <= 255, "number of classes {} must be in 1..255", num_classes);
  for (const auto* ids : {&dynamic_classes, &movable_classes}) {
    for (int id : *ids) {
      DLSLAM_CHECK(id >= 0 && id < num_classes, "class id {} (in {}) out of range for {} classes", id,
                   fmt::join(*ids, ","), num_classes);
    }
  }
  for (int id : dynamic_classes) {
    DLSLAM_CHECK(std::find(movable_classes.begin(), movable_classes.end(), id) == movable_classes.end(),
                 "class {} is listed as both a-priori dynamic and movable", id);
  }
  DLSLAM_CHECK(dynamic_margin_px >= 0 && dynamic_margin_px <= 100, "dynamic mask margin {} px must be in 0..100",
               dynamic_margin_px);
  DLSLAM_CHECK(threads >= 0 && threads <= 256, "thread count {} must be in 0..256 (0 = OpenCV's default)",
               threads);
  DLSLAM_CHECK_GE(min_image_side, 1, "smallest frame side [px]");
}

std::unique_ptr<Segmenter> MakeSegmenter(const SegmenterOptions& options) {
  options.Check();
  SegmenterOptions resolved = options;
  if (resolved.model_path.empty()) {
    resolved.model_path = io::FindModelFile(kDefaultModelFile);
  }
  return std::make_unique<OnnxSegmenter>(resolved);
}

}  // namespace dlslam::semantic
