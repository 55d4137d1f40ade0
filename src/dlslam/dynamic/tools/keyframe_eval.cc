#include "dlslam/dynamic/tools/keyframe_eval.h"

#include <chrono>
#include <cmath>

#include "dlslam/synth/renderer.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic::evaluation {

ReferenceView MakeReferenceView(const cv::Mat& depth, const std::vector<cv::KeyPoint>& keypoints,
                                const CameraIntrinsics& camera, const SE3d& world_from_cam,
                                std::uint64_t first_id, double min_depth_m, double max_depth_m) {
  DLSLAM_CHECK(depth.type() == CV_32FC1, "MakeReferenceView: depth must be CV_32FC1");
  ReferenceView view;
  view.cam_from_world = world_from_cam.Inverse();
  view.points.reserve(keypoints.size());
  std::uint64_t id = first_id;
  for (const cv::KeyPoint& k : keypoints) {
    const int u = static_cast<int>(std::lround(k.pt.x));
    const int v = static_cast<int>(std::lround(k.pt.y));
    if (u < 0 || v < 0 || u >= depth.cols || v >= depth.rows) continue;
    const double z = depth.at<float>(v, u);
    if (!(z >= min_depth_m && z <= max_depth_m)) continue;
    view.points.push_back({world_from_cam * camera.Unproject({k.pt.x, k.pt.y}, z), id++});
  }
  return view;
}

double KeypointScores::Precision() const {
  const long predicted = true_positive + false_positive;
  return predicted == 0 ? 1.0 : static_cast<double>(true_positive) / static_cast<double>(predicted);
}

double KeypointScores::Recall() const {
  const long actual = true_positive + false_negative;
  return actual == 0 ? 1.0 : static_cast<double>(true_positive) / static_cast<double>(actual);
}

KeypointScores& KeypointScores::operator+=(const KeypointScores& other) {
  true_positive += other.true_positive;
  false_positive += other.false_positive;
  false_negative += other.false_negative;
  true_negative += other.true_negative;
  return *this;
}

KeypointScores ScoreKeypoints(const cv::Mat& predicted, const std::vector<cv::KeyPoint>& keypoints,
                              const cv::Mat& truth) {
  DLSLAM_CHECK(predicted.type() == CV_8UC1 && truth.type() == CV_8UC1 &&
                   predicted.size() == truth.size(),
               "ScoreKeypoints: need two CV_8UC1 masks of one size");
  KeypointScores scores;
  for (const cv::KeyPoint& k : keypoints) {
    const int u = std::clamp(static_cast<int>(std::lround(k.pt.x)), 0, truth.cols - 1);
    const int v = std::clamp(static_cast<int>(std::lround(k.pt.y)), 0, truth.rows - 1);
    const bool p = predicted.at<std::uint8_t>(v, u) != 0;
    const bool t = truth.at<std::uint8_t>(v, u) != 0;
    if (p && t) ++scores.true_positive;
    if (p && !t) ++scores.false_positive;
    if (!p && t) ++scores.false_negative;
    if (!p && !t) ++scores.true_negative;
  }
  return scores;
}

const SynthFrameCache::Frame& SynthFrameCache::Get(int index) {
  auto it = frames_.find(index);
  if (it != frames_.end()) return it->second;
  Frame frame;
  frame.rendered = sequence_.Render(index);
  frame.keypoints = orb_.Extract(frame.rendered.colour).keypoints;
  frame.moving = cv::Mat::zeros(frame.rendered.mask.size(), CV_8UC1);
  for (int v = 0; v < frame.moving.rows; ++v) {
    for (int u = 0; u < frame.moving.cols; ++u) {
      if (synth::MaskMoving(frame.rendered.mask.at<std::uint8_t>(v, u))) {
        frame.moving.at<std::uint8_t>(v, u) = 255;
      }
    }
  }
  return frames_.emplace(index, std::move(frame)).first->second;
}

void SynthEvalOptions::Check() const {
  DLSLAM_CHECK(frames >= 1 && step >= 1 && reference_count >= 1 && reference_stride >= 1,
               "SynthEvalOptions: frames {}, step {}, reference_count {}, reference_stride {} "
               "must be >= 1",
               frames, step, reference_count, reference_stride);
  DLSLAM_CHECK(first_frame >= reference_count * reference_stride,
               "SynthEvalOptions: first_frame {} < reference_count * reference_stride = {}",
               first_frame, reference_count * reference_stride);
  fusion.Check();
}

SynthEvalStats EvaluateOnSynth(SynthFrameCache& cache, const GeometryOptions& geometry,
                               const SynthEvalOptions& options) {
  options.Check();
  const synth::SynthSequence& sequence = cache.sequence();
  const CameraIntrinsics& camera = sequence.options().camera;
  const int last = options.first_frame + (options.frames - 1) * options.step;
  DLSLAM_CHECK_LT(last, sequence.size(), "EvaluateOnSynth: the sequence is too short");
  GeometryDetector detector(geometry);
  SynthEvalStats stats;
  std::vector<ReferenceView> references;
  for (int i = options.first_frame; i <= last; i += options.step) {
    references.clear();
    for (int r = 1; r <= options.reference_count; ++r) {
      const int k = i - r * options.reference_stride;
      const SynthFrameCache::Frame& keyframe = cache.Get(k);
      references.push_back(MakeReferenceView(keyframe.rendered.depth, keyframe.keypoints, camera,
                                             keyframe.rendered.world_from_cam,
                                             static_cast<std::uint64_t>(k) << 20));
    }
    const SynthFrameCache::Frame& current = cache.Get(i);
    const auto start = std::chrono::steady_clock::now();
    GeometryResult result = detector.Detect(current.rendered.depth, camera,
                                            current.rendered.world_from_cam.Inverse(), references);
    stats.detect_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const cv::Mat mask = FuseDynamicMasks({}, result, options.fusion);
    stats.scores += ScoreKeypoints(mask, current.keypoints, current.moving);
    stats.points_projected += result.points_projected;
    stats.points_tested += result.points_tested;
    stats.points_dynamic += result.points_dynamic;
    for (std::size_t k = 0; k < result.points.size(); ++k) {
      if (result.labels[k] != PointLabel::kDynamic) continue;
      const int u = static_cast<int>(std::lround(result.points[k].pixel.x()));
      const int v = static_cast<int>(std::lround(result.points[k].pixel.y()));
      // A 5x5 patch: the depth that decided may lie up to 2 px away.
      const cv::Rect patch = cv::Rect(u - 2, v - 2, 5, 5) & cv::Rect(0, 0, current.moving.cols, current.moving.rows);
      if (cv::countNonZero(current.moving(patch)) > 0) ++stats.dynamic_on_movers;
    }
    ++stats.frames;
    stats.last_mask = mask;
    stats.last_result = std::move(result);
  }
  return stats;
}

}  // namespace dlslam::dynamic::evaluation
