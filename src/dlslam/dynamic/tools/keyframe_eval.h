#pragma once
// Evaluation helpers of the dynamic module (tools and tests, not the
// product): reference views from keypoints with depth, keypoint-level
// precision / recall of a dynamic mask, and a run of the geometry detector
// over rendered frames of a synthetic sequence with ground-truth poses.

#include <opencv2/core.hpp>

#include <cstdint>
#include <map>
#include <vector>

#include "dlslam/data/camera.h"
#include "dlslam/dynamic/geometry_detector.h"
#include "dlslam/dynamic/mask_fusion.h"
#include "dlslam/features/orb_extractor.h"
#include "dlslam/geometry/se3.h"
#include "dlslam/synth/sequence.h"

namespace dlslam::dynamic::evaluation {

// A keyframe: every keypoint with a valid depth (depth image at the rounded
// keypoint pixel, in [min_depth_m, max_depth_m]) lifted into the world;
// ids first_id, first_id + 1, ...
ReferenceView MakeReferenceView(const cv::Mat& depth, const std::vector<cv::KeyPoint>& keypoints,
                                const CameraIntrinsics& camera, const SE3d& world_from_cam,
                                std::uint64_t first_id, double min_depth_m = 0.1,
                                double max_depth_m = 6.0);

// Keypoints counted by (predicted dynamic, truly dynamic).
struct KeypointScores {
  long true_positive = 0, false_positive = 0, false_negative = 0, true_negative = 0;
  double Precision() const;  // 1 when nothing was predicted
  double Recall() const;     // 1 when nothing was truly dynamic
  KeypointScores& operator+=(const KeypointScores& other);
};

// `predicted`: CV_8UC1, non-zero = dynamic. `truth`: CV_8UC1, non-zero = dynamic.
KeypointScores ScoreKeypoints(const cv::Mat& predicted, const std::vector<cv::KeyPoint>& keypoints,
                              const cv::Mat& truth);

// Rendered frames with their ORB keypoints and the moving-surface truth
// (synth::MaskMoving), rendered once and kept.
class SynthFrameCache {
 public:
  struct Frame {
    synth::RenderedFrame rendered;
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat moving;  // CV_8UC1, 255 where a surface moved
  };
  explicit SynthFrameCache(const synth::SynthSequence& sequence) : sequence_(sequence) {}
  const Frame& Get(int index);
  const synth::SynthSequence& sequence() const { return sequence_; }

 private:
  const synth::SynthSequence& sequence_;
  features::OrbExtractor orb_;
  std::map<int, Frame> frames_;
};

struct SynthEvalOptions {
  int first_frame = 30;       // first evaluated frame (needs earlier frames as references)
  int frames = 30;            // frames evaluated
  int step = 1;               // between evaluated frames
  int reference_count = 5;    // keyframes per evaluated frame
  int reference_stride = 6;   // frames between keyframes (frame i - stride, i - 2 stride, ...)
  FusionOptions fusion = [] {  // how the geometry mask becomes the final mask
    FusionOptions f;
    f.policy = FusionPolicy::kGeometryOnly;
    return f;
  }();
  void Check() const;  // throws dlslam::Error
};

struct SynthEvalStats {
  KeypointScores scores;  // current-frame ORB keypoints vs. MaskMoving
  long points_projected = 0;
  long points_tested = 0;
  long points_dynamic = 0;
  long dynamic_on_movers = 0;  // dynamic points whose pixel is truly moving
  double detect_ms = 0;   // sum of Detect() wall times [ms]
  int frames = 0;
  cv::Mat last_mask;      // the final mask of the last frame
  GeometryResult last_result;
};

// Runs one detector (its pheromone persists over the frames) with
// ground-truth poses.
SynthEvalStats EvaluateOnSynth(SynthFrameCache& cache, const GeometryOptions& geometry,
                               const SynthEvalOptions& options);

}  // namespace dlslam::dynamic::evaluation
