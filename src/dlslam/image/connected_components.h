#pragma once
// The 8-connected components of a binary mask, labelled from runs of set
// pixels joined by union-find.
//
// Why our own: cv::connectedComponents runs its parallel variant on OpenCV's
// TBB pool for any image of more than a few rows. On two cores already busy
// with tracking, the network and mapping that buys nothing, and a pool TSan
// cannot see through reports its workers' buffers as races with the caller.
// Runs make the mask's empty stretches cheap (most of a frame).

#include <opencv2/core.hpp>

#include <vector>

namespace dlslam::image {

// `mask`: CV_8UC1, any size; a pixel is set when it is not 0. Writes into
// `labels` (CV_32SC1, reallocated only when its size or type differ) 0 for
// unset pixels and 1..n-1 for the components (numbered in the order their
// first pixel comes, row by row), and returns n, the count with the
// background, as cv::connectedComponents does. `areas`, when given, gets n
// entries: the pixel count of each label (areas[0] the unset pixels).
// Throws dlslam::Error on another type.
int LabelComponents(const cv::Mat& mask, cv::Mat& labels, std::vector<int>* areas = nullptr);

}  // namespace dlslam::image
