#include "dlslam/semantic/label_maps.h"

#include <opencv2/imgproc.hpp>

#include "dlslam/image/disc_dilation.h"
#include "dlslam/util/check.h"

namespace dlslam::semantic {

namespace {
// Above this margin [px] DilateMask thresholds a distance transform.
constexpr int kLargeMarginPx = 8;
}  // namespace

cv::Mat ArgmaxLabels(const cv::Mat& logits) {
  DLSLAM_CHECK_EQ(logits.dims, 4, "logits must be a 1 x C x H x W blob");
  DLSLAM_CHECK_EQ(logits.type(), CV_32F, "logits must be float");
  DLSLAM_CHECK_EQ(logits.size[0], 1, "one image per blob");
  const int classes = logits.size[1];
  const int height = logits.size[2];
  const int width = logits.size[3];
  DLSLAM_CHECK(classes >= 1 && classes <= 255, "{} classes do not fit 8-bit labels", classes);
  DLSLAM_CHECK(logits.isContinuous(), "logits blob must be continuous");

  // Each class plane is a 2-D header on the blob's memory (no copies); a
  // running maximum and a strict comparison keep the first class on ties.
  auto plane = [&](int c) {
    return cv::Mat(height, width, CV_32F, const_cast<float*>(logits.ptr<float>(0, c)));
  };
  cv::Mat best = plane(0).clone();
  cv::Mat labels(height, width, CV_8UC1, cv::Scalar(0));
  cv::Mat greater;
  for (int c = 1; c < classes; ++c) {
    const cv::Mat scores = plane(c);
    cv::compare(scores, best, greater, cv::CMP_GT);
    labels.setTo(c, greater);
    cv::max(best, scores, best);
  }
  return labels;
}

cv::Mat ClassMask(const cv::Mat& labels, const std::vector<int>& class_ids) {
  DLSLAM_CHECK_EQ(labels.type(), CV_8UC1, "labels must be 8-bit, one channel");
  cv::Mat table(1, 256, CV_8UC1, cv::Scalar(0));
  for (int id : class_ids) {
    DLSLAM_CHECK(id >= 0 && id <= 255, "class id {} out of range", id);
    table.at<uchar>(id) = 255;
  }
  cv::Mat mask;
  cv::LUT(labels, table, mask);
  return mask;
}

cv::Mat DilateMask(const cv::Mat& mask, int margin_px) {
  DLSLAM_CHECK_GE(margin_px, 0, "dilation margin [px]");
  if (margin_px == 0) return mask;
  if (margin_px > kLargeMarginPx) {
    // A disc dilation costs O(radius) per pixel; the exact Euclidean distance
    // to the mask costs O(1), so wide margins (long propagation gaps) threshold it.
    cv::Mat distance;
    cv::distanceTransform(mask == 0, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    return distance <= static_cast<float>(margin_px);
  }
  return image::DilateDisc(mask, margin_px);
}

SegmentationResult ResultFromLabels(const cv::Mat& network_labels, cv::Size frame_size,
                                    const SegmenterOptions& options) {
  DLSLAM_CHECK(!network_labels.empty() && frame_size.area() > 0, "empty label map or frame");
  auto to_frame = [&](const cv::Mat& small) {
    if (small.size() == frame_size) return small;
    cv::Mat resized;
    cv::resize(small, resized, frame_size, 0, 0, cv::INTER_NEAREST);
    return resized;
  };
  // Masks are looked up at the network resolution (fewer pixels) and then
  // resized: with nearest neighbour both orders give the same pixels.
  SegmentationResult result;
  result.labels = to_frame(network_labels);
  result.dynamic_mask = DilateMask(to_frame(ClassMask(network_labels, options.dynamic_classes)),
                                   options.dynamic_margin_px);
  result.movable_mask = to_frame(ClassMask(network_labels, options.movable_classes));
  return result;
}

SegmentationResult PropagateResult(const SegmentationResult& segmented, int gap, int grow_px_per_frame) {
  DLSLAM_CHECK_GE(gap, 0, "frames since the segmented one");
  DLSLAM_CHECK_GE(grow_px_per_frame, 0, "propagation growth [px per frame]");
  SegmentationResult result = DeepCopy(segmented);
  if (gap * grow_px_per_frame > 0) result.dynamic_mask = DilateMask(segmented.dynamic_mask, gap * grow_px_per_frame);
  result.propagated_from = gap;
  result.seconds = 0.0;
  return result;
}

SegmentationResult DeepCopy(const SegmentationResult& result) {
  SegmentationResult copy = result;
  copy.labels = result.labels.clone();
  copy.dynamic_mask = result.dynamic_mask.clone();
  copy.movable_mask = result.movable_mask.clone();
  return copy;
}

}  // namespace dlslam::semantic
