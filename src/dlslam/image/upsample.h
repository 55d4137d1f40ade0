#pragma once
// A coarse mask back at full size: each cell of `grid` becomes a
// factor x factor block, cropped to `size`. The same pixels as cv::resize
// with INTER_NEAREST to grid.size() * factor followed by the crop (that is
// what the grid-based checks did), at a fraction of its cost: rows of
// repeated bytes and row copies (160x120 -> 640x480: 8 us against
// cv::resize's 114-118 us, dlslam_bench_image).

#include <opencv2/core.hpp>

namespace dlslam::image {

// `grid`: CV_8UC1. `factor` >= 1; `size` at most grid.size() * factor.
// Writes into `out` (reallocated only when its size or type differ; not
// `grid` itself). Throws dlslam::Error otherwise.
void UpsampleNearest(const cv::Mat& grid, int factor, cv::Size size, cv::Mat& out);
cv::Mat UpsampleNearest(const cv::Mat& grid, int factor, cv::Size size);

}  // namespace dlslam::image
