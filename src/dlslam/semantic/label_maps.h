#pragma once
// Post-processing of a segmentation network's output, shared by the
// backends: argmax over the class planes, class masks, resizing to the frame
// and the dilation margin. All whole-image OpenCV operations (no per-pixel
// loops).

#include <opencv2/core.hpp>
#include <vector>

#include "dlslam/semantic/segmenter.h"

namespace dlslam::semantic {

// Label = index of the largest class score (the first one on ties, as
// numpy's argmax). logits: CV_32F blob 1 x C x H x W with 1 <= C <= 255, as
// cv::dnn returns it. Returns CV_8UC1 H x W.
cv::Mat ArgmaxLabels(const cv::Mat& logits);

// 255 where the label is one of `class_ids`, 0 elsewhere (CV_8UC1).
cv::Mat ClassMask(const cv::Mat& labels, const std::vector<int>& class_ids);

// Grows a 0/255 mask by `margin_px`: every pixel within that distance of the
// mask (a disc structuring element; above 8 px the exact Euclidean distance,
// which is faster for wide discs). Margin 0 returns the mask unchanged.
cv::Mat DilateMask(const cv::Mat& mask, int margin_px);

// The result for a frame of `frame_size` from the network's label map (at the
// network resolution): labels and masks resized with nearest neighbour, the
// dynamic mask dilated by options.dynamic_margin_px.
SegmentationResult ResultFromLabels(const cv::Mat& network_labels, cv::Size frame_size,
                                    const SegmenterOptions& options);

// A result for a frame `gap` frames after `segmented` (which was segmented
// itself): same labels, dynamic mask grown by gap * grow_px_per_frame more.
// Shares no pixel memory with `segmented`.
SegmentationResult PropagateResult(const SegmentationResult& segmented, int gap,
                                   int grow_px_per_frame);

// A copy that shares no pixel memory with `result` (cv::Mat copies share it).
SegmentationResult DeepCopy(const SegmentationResult& result);

}  // namespace dlslam::semantic
