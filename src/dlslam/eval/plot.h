#pragma once
// Plots of evaluation results, as SVG text or as an image. Pure functions:
// the caller writes the file (io::WriteFileAtomically, EncodePng).
//   ATE: top view (x-y) and side view (x-z) of the aligned estimate over the
//        ground truth, each estimate pose coloured by its error (colour bar),
//        and the error over time.
//   RPE: translation and rotation error over time.

#include <opencv2/core.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "dlslam/eval/ate.h"
#include "dlslam/eval/rpe.h"

namespace dlslam::eval {

enum class PlotFormat { kSvg, kPng };

// By extension (.svg / .png, any case); throws dlslam::Error for others.
PlotFormat PlotFormatFromPath(const std::filesystem::path& path);

std::string AtePlotSvg(const AteResult& result);
cv::Mat AtePlotImage(const AteResult& result);  // 8-bit BGR
std::string RpePlotSvg(const RpeResult& result);
cv::Mat RpePlotImage(const RpeResult& result);  // 8-bit BGR

// PNG bytes of an 8-bit image; throws dlslam::Error if encoding fails.
std::vector<unsigned char> EncodePng(const cv::Mat& image);

}  // namespace dlslam::eval
