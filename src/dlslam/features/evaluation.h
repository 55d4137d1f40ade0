#pragma once
// Detector and descriptor quality under a known image transform (rotation,
// scale): repeatability and matching precision / recall, for comparing our
// extractor with cv::ORB in tests and tools/orb_eval.

#include <opencv2/core.hpp>

#include <vector>

#include "dlslam/features/matching.h"

namespace dlslam::features {

// An image rotated by `angle_deg` (counter-clockwise on screen) about its
// centre and scaled by `scale`, on a canvas that holds all of it.
struct WarpedImage {
  cv::Mat image;           // same type as the source, black outside the source
  cv::Mat valid;           // CV_8UC1, 255 where the canvas shows the source, eroded by `margin`
  cv::Matx23d to_warped;   // maps source pixels to canvas pixels
};
WarpedImage WarpImage(const cv::Mat& source, double angle_deg, double scale, int margin = 16);

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;  // CV_8UC1 n x 32
};

struct TransformScores {
  int keypoints_a = 0;      // keypoints of the source image that land on the valid canvas
  int keypoints_b = 0;      // keypoints of the warped image on its valid area
  int repeated = 0;         // source keypoints with a warped keypoint within the tolerance
  // The same count for positions shifted by 20 px (mean of 4 diagonal
  // shifts): repeatability by chance, higher for clustered keypoints.
  double repeated_by_chance = 0.0;
  int matches = 0;          // matches that pass the matcher's tests
  int correct_matches = 0;  // of those, the ones within the tolerance of the true position
  double repeatability() const;            // repeated / keypoints_a
  double chance_repeatability() const;     // repeated_by_chance / keypoints_a
  double precision() const;      // correct_matches / matches
  double recall() const;         // correct_matches / repeated
};

// Scores features `a` of a source image against features `b` of its warped
// copy: a keypoint pair corresponds when the mapped source position is
// within `tolerance_px` of the warped one.
TransformScores ScoreUnderTransform(const Features& a, const Features& b, const WarpedImage& warp,
                                    double tolerance_px = 3.0,
                                    const MatchOptions& match_options = {});

}  // namespace dlslam::features
