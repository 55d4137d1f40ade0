#pragma once
// Images for the features tests: a real 640x480 frame when the shared data
// is there, and a synthetic textured one that is always available.

#include <opencv2/core.hpp>

#include <optional>
#include <string>

namespace dlslam::features::testing {

// Random overlapping rectangles and ellipses of random grey levels, lightly
// smoothed: corners everywhere, deterministic for a seed. CV_8UC1.
cv::Mat SyntheticTexture(int width = 640, int height = 480, unsigned seed = 7);

// 7-Scenes redkitchen frame `name` (e.g. "0.000000.jpg") as grey, or nullopt
// when the shared data is absent.
std::optional<cv::Mat> RealFrame(const std::string& name);

}  // namespace dlslam::features::testing
