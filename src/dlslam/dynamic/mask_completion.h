#pragma once
// Completes a segmentation network's person mask with the depth image: the
// pixels beside a segment that lie at the segment's depth are taken to be
// the same body.
//
// The network misses parts of people that the tracker then follows: a scarf
// end or a hem over a table, an arm, boots, legs seen below a table edge
// (separated from the torso by the occluder). On the semi-real kitchens
// those were the keypoints on people that tracking kept (median 7 a frame,
// up to 327), and they slid the camera with the walkers. A person is a body
// of bounded size at one depth: a pixel joins a segment when it lies within
// reach_m of it (measured at the segment's depth) and its depth is within the
// segment's depth band. Static structure at the person's depth right beside
// them goes too: the price of a mask that covers the whole body.

#include <opencv2/core.hpp>

namespace dlslam::dynamic {

struct MaskCompletionOptions {
  // Off by default: on the 12 semi-real kitchens it kept ~40 % fewer
  // keypoints on people but took ~5 % more of the image (tables beside
  // people, at their depth) and the ATE did not improve beyond the runs'
  // chaos (docs/real-data.md, "Completing the person mask with depth").
  bool enabled = false;
  // Reach from a segment's outline [m, lateral, at the segment's median
  // depth]: about the part of a body the network misses beside what it
  // found (an arm, a scarf, the feet).
  double reach_m = 0.15;
  // A pixel joins when its depth lies between the segment's depth quartiles
  // widened by this margin [m] (a body is ~0.3 m deep).
  double depth_margin_m = 0.15;
  // Segments smaller than this are not completed [px]: their depth says
  // little (a sliver of a person at the border, a misfire).
  int min_segment_pixels = 400;
  // Valid depths [m]; others neither describe a segment nor join one.
  double min_depth_m = 0.1;
  double max_depth_m = 8.0;
  // Work on every pixel_step-th pixel in u and v (1 or 2): 2 is ~4x faster
  // and coarsens only the added outline by a pixel, which the fusion's
  // dilation covers.
  int pixel_step = 2;

  // Throws dlslam::Error naming the field and its value.
  void Check() const;
};

// `mask`: CV_8UC1, non-zero = person (the network's dynamic mask). `depth`:
// CV_32FC1 metres (0 / NaN = invalid), the same size. `focal_px`: the
// camera's focal length (turns reach_m into pixels). Returns the mask with the
// completed pixels added, CV_8UC1 0 / 255; the input unchanged (a copy, 0 /
// 255) when there is nothing to complete or options.enabled is false. Throws
// dlslam::Error on inputs of the wrong type or size.
cv::Mat CompleteMaskByDepth(const cv::Mat& mask, const cv::Mat& depth, double focal_px,
                            const MaskCompletionOptions& options);

}  // namespace dlslam::dynamic
