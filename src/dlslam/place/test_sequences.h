#pragma once
// Frames for the place-recognition test and benchmark: the 7-Scenes
// redkitchen excerpt (shared data) with ground truth, and synthetic rooms.

#include <opencv2/core.hpp>

#include <cstdint>
#include <filesystem>
#include <vector>

#include "dlslam/geometry/se3.h"
#include "dlslam/place/revisit_evaluation.h"
#include "dlslam/place/vocabulary.h"
#include "dlslam/synth/scene.h"

namespace dlslam::place::testing {

// Every `stride`-th frame of a TUM-layout folder with rgb.txt and a
// groundtruth.txt holding one pose per image (7-Scenes excerpt), as BoW
// vectors of ORB features (default extractor).
std::vector<RevisitFrame> LoadRevisitFrames(const std::filesystem::path& dir, int stride,
                                            const Vocabulary& vocabulary);

// A 640x480 colour frame of `scene` seen from `world_from_cam`, with sensor
// noise drawn from `noise_seed`.
cv::Mat RenderColour(const synth::Scene& scene, const SE3d& world_from_cam, std::uint32_t noise_seed);

}  // namespace dlslam::place::testing
