#pragma once
// ORB features as ORB-SLAM3 extracts them, written by us: an 8-level image
// pyramid, FAST-9 on a grid with a threshold fallback, an even spread per
// level by a quadtree, intensity-centroid orientation and steered BRIEF with
// a learned test pattern. Design and measurements: docs/features.md.
//
//   OrbExtractor orb;                       // ORB-SLAM's defaults for 640x480
//   OrbFeatures f = orb.Extract(grey);      // f.keypoints, f.descriptors (n x 32)

#include <opencv2/core.hpp>

#include <array>
#include <span>
#include <vector>

#include "dlslam/features/brief_descriptor.h"
#include "dlslam/features/fast_detector.h"
#include "dlslam/features/orb_options.h"
#include "dlslam/features/orb_pattern.h"

namespace dlslam::features {

struct OrbFeatures {
  // Level-0 pixel coordinates; octave = pyramid level, size = 31 px times
  // the level's scale, angle [deg, 0..360), response = FAST score.
  std::vector<cv::KeyPoint> keypoints;
  // CV_8UC1, keypoints.size() x kDescriptorBytes; row i describes keypoint i.
  cv::Mat descriptors;
};

// Not thread-safe: an extractor keeps its pyramid and scratch memory between
// calls (use one per thread).
class OrbExtractor {
 public:
  // Throws dlslam::Error for invalid options (OrbOptions::Check).
  explicit OrbExtractor(const OrbOptions& options = {},
                        std::span<const PatternTest> pattern = LearnedOrbPattern());

  // `image`: CV_8UC1 grey, or CV_8UC3 / CV_8UC4 in OpenCV's BGR(A) order,
  // converted to grey. Anything else (16-bit, float, other channel counts),
  // an empty image or one smaller than 2 * edge_border + 1 px on a side
  // throws dlslam::Error. `exclusion_mask`: empty, or CV_8UC1 of the image's
  // size; no keypoint is kept where it is non-zero (e.g. dynamic objects),
  // and the level's budget goes to the rest of the image.
  OrbFeatures Extract(const cv::Mat& image, const cv::Mat& exclusion_mask = cv::Mat());
  // The same, reusing `out`'s memory.
  void Extract(const cv::Mat& image, const cv::Mat& exclusion_mask, OrbFeatures& out);

  // Keypoints of the last Extract call's image outside `exclusion_mask`
  // (CV_8UC1, the image's size), as Extract(image, exclusion_mask) would give
  // them: when the mask contains that call's exclusion mask (a removal grown
  // after a first extraction), its FAST corners are filtered again, so only
  // the spread over the image and the descriptors cost anything (about a
  // third of Extract); otherwise FAST runs again on the kept pyramid. The
  // image must not have been changed in between (a grey image's pyramid
  // shares its pixels). Throws dlslam::Error before any Extract call.
  OrbFeatures Reextract(const cv::Mat& exclusion_mask);

  // Extract(image, exclusion_mask) for the image of `source`'s last Extract
  // call, on `source`'s pyramid and smoothed levels instead of building them
  // again (~1 ms at 640x480): e.g. a second extraction with other FAST
  // thresholds. Needs CanExtractOn(source) and an Extract call of `source`
  // first; `source` must not extract again until this extractor has
  // extracted on its own (the levels are shared). Throws dlslam::Error otherwise.
  OrbFeatures ExtractOn(const OrbExtractor& source, const cv::Mat& exclusion_mask);
  // The pyramids agree: the same levels, scale factor and edge border.
  bool CanExtractOn(const OrbExtractor& source) const;

  // Descriptors of given keypoints (level = octave, position pt / scale
  // rounded, angle as given; e.g. another detector's) on this extractor's
  // smoothed pyramid of `image`. Keypoints whose level does not exist or whose
  // patch leaves the level are dropped. Throws like Extract for a bad image.
  OrbFeatures Describe(const cv::Mat& image, const std::vector<cv::KeyPoint>& keypoints);

  const OrbOptions& options() const { return options_; }
  // scale_factor^level for each level.
  const std::vector<double>& level_scales() const { return level_scales_; }
  // The grey pyramid and its Gaussian-smoothed twin (7x7, sigma 2) of the
  // last Extract call (level 0 shares the caller's grey image); levels too
  // small for keypoints, and smoothed levels without keypoints, are empty
  // (after a Reextract, a smoothed level may outlive its keypoints).
  const std::vector<cv::Mat>& pyramid() const { return pyramid_; }
  const std::vector<cv::Mat>& smoothed_pyramid() const { return smoothed_; }

 private:
  void PrepareImage(const cv::Mat& image);  // checks, grey, pyramid
  void BuildPyramid(const cv::Mat& grey);
  void SmoothLevel(size_t level);
  void SetExclusion(const cv::Mat& exclusion_mask);  // checks; excluded_ and its integral
  // On the current pyramid; `known`: see Describe.
  void DetectSelectDescribe(const cv::Mat& exclusion_mask, OrbFeatures& out, const OrbExtractor* known);
  void DetectLevel(int level, const cv::Mat& exclusion_mask);
  // Keeps the level's corners outside the mask, spread by the quadtree.
  void SelectLevel(int level, const cv::Mat& exclusion_mask);
  // Of the selected corners of every level; a corner that `known`'s
  // described_ holds (an extractor on the same pyramid with the same tests,
  // may be this one or null) is copied, not computed. Leaves described_
  // holding both.
  void Describe(OrbFeatures& out, const OrbExtractor* known);

  OrbOptions options_;
  SteeredBrief brief_;
  std::vector<double> level_scales_;
  std::vector<int> level_targets_;
  std::vector<cv::Mat> pyramid_, smoothed_;
  cv::Mat blur_kernel_;
  // Scratch kept between calls.
  cv::Mat grey_;
  FastScratch fast_scratch_;
  std::vector<std::vector<FastCorner>> level_corners_;  // selected: outside the mask, spread
  // The last Extract's corners per level before the mask and the spread,
  // and its exclusion (0/255, empty for none): what Reextract starts from.
  std::vector<std::vector<FastCorner>> detected_;
  cv::Mat detected_exclusion_;
  cv::Size extracted_size_;  // empty before the first Extract
  bool borrowed_ = false;   // pyramid_ and smoothed_ share another extractor's (ExtractOn)
  cv::Mat excluded_, excluded_integral_;  // the exclusion mask as 0/255, and its integral image
  // Every corner described on the current pyramid, per level sorted by its
  // pixel (key = y * level width + x): a re-extraction of the same image
  // (Reextract, or another extractor's ExtractOn this one) keeps most of the
  // first one's corners, and describes only the others.
  struct Described {
    int key;
    float angle;
    std::array<uchar, kDescriptorBytes> descriptor;
  };
  std::vector<std::vector<Described>> described_;
};

}  // namespace dlslam::features
