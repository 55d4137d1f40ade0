#include "dlslam/system/dynamic_stage.h"

#include <algorithm>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam {

std::optional<double> DynamicStats::precision() const {
  const std::int64_t removed = true_positives + false_positives;
  if (frames_with_truth == 0 || removed == 0) return std::nullopt;
  return static_cast<double>(true_positives) / static_cast<double>(removed);
}

std::optional<double> DynamicStats::recall() const {
  const std::int64_t moving = true_positives + false_negatives;
  if (frames_with_truth == 0 || moving == 0) return std::nullopt;
  return static_cast<double>(true_positives) / static_cast<double>(moving);
}

std::optional<double> DynamicStats::image_share_removed() const {
  if (pixels_total == 0) return std::nullopt;
  return static_cast<double>(pixels_removed) / static_cast<double>(pixels_total);
}

dynamic::ReferenceView MakeReferenceView(const KeyFrameSnapshot& keyframe) {
  DLSLAM_CHECK(keyframe.frame != nullptr);
  const Frame& frame = *keyframe.frame;
  DLSLAM_CHECK_EQ(keyframe.points.size(), frame.size(), "one map point slot per keypoint");
  dynamic::ReferenceView view;
  view.cam_from_world = keyframe.cam_from_world;
  const SE3d world_from_cam = keyframe.cam_from_world.Inverse();
  view.points.reserve(frame.size());
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const std::optional<Eigen::Vector3d> p_cam = frame.Unproject(i);
    if (!p_cam) continue;
    view.points.push_back({world_from_cam * *p_cam, keyframe.points[i]});
  }
  return view;
}

DynamicStage::DynamicStage(const DynamicOptions& options, const CameraIntrinsics& camera, Map* map,
                           const Tracker* tracker, StageTimings* timings)
    : options_(options),
      camera_(camera),
      map_(map),
      tracker_(tracker),
      timings_(timings),
      detector_(options.GeometryInMode()),
      free_space_(camera, options.geometry.free_space) {
  options_.Check();
  DLSLAM_CHECK(map_ != nullptr && tracker_ != nullptr && timings_ != nullptr);
  stats_.mode = options_.mode;
  stats_.search = options_.geometry.search;
  stats_.fusion = options_.fusion.policy;
}

double DynamicPrior::removed_share() const {
  return removal.empty() ? 0.0 : cv::countNonZero(removal) / static_cast<double>(removal.total());
}

dynamic::FusionOptions DynamicStage::Fusion() const {
  dynamic::FusionOptions fusion = options_.fusion;
  if (options_.mode == DynamicMode::kSemantic) fusion.policy = dynamic::FusionPolicy::kSemanticOnly;
  if (options_.mode == DynamicMode::kGeometry) fusion.policy = dynamic::FusionPolicy::kGeometryOnly;
  return fusion;
}

DynamicPrior DynamicStage::TakePrior(const DynamicInputs& inputs, const cv::Mat& depth) {
  DynamicPrior prior;
  if (!UsesSemanticPrior(options_.mode) || !inputs.semantic_prior) return prior;
  Stopwatch watch;
  prior.masks = inputs.semantic_prior();
  timings_->Add("semantic_wait", watch.ElapsedMs());
  const auto check = [this](const cv::Mat& mask, const char* what) {
    if (mask.empty()) return;
    DLSLAM_CHECK(mask.type() == CV_8UC1 && mask.cols == camera_.width && mask.rows == camera_.height,
                 "the {} must be 8-bit single-channel {}x{}, got type {} {}x{}", what, camera_.width, camera_.height,
                 mask.type(), mask.cols, mask.rows);
  };
  check(prior.masks.dynamic, "semantic prior");
  check(prior.masks.movable, "movable-class mask");
  if (prior.masks.dynamic.empty() || cv::countNonZero(prior.masks.dynamic) == 0) return prior;
  if (options_.completion.enabled && !depth.empty()) {
    watch = Stopwatch();
    prior.masks.dynamic = dynamic::CompleteMaskByDepth(prior.masks.dynamic, depth, camera_.fx, options_.completion);
    timings_->Add("mask_completion", watch.ElapsedMs());
  }
  const dynamic::FusionOptions fusion = Fusion();
  prior.removal = dynamic::FuseDynamicMasks({prior.masks.dynamic, {}}, {}, fusion);
  prior.final =
      fusion.policy == dynamic::FusionPolicy::kUnion || fusion.policy == dynamic::FusionPolicy::kSemanticOnly;
  return prior;
}

DynamicRemoval DynamicStage::Process(const Frame& frame, const cv::Mat& depth, const DynamicInputs& inputs) {
  return Process(frame, depth, TakePrior(inputs, depth), inputs.moving_truth);
}

DynamicRemoval DynamicStage::Process(const Frame& frame, const cv::Mat& depth, const DynamicPrior& prior,
                                     const cv::Mat& moving_truth) {
  stats_.keypoints_total += static_cast<std::int64_t>(frame.size());
  DynamicRemoval removal;
  if (options_.mode != DynamicMode::kOrb) {
    dynamic::GeometryResult geometry;  // empty mask: the check did not run
    if (UsesGeometry(options_.mode) && !depth.empty()) {
      // The first pose estimate must not lean on what the network already
      // knows to move: it sees the frame without the prior's keypoints
      // (movable objects are mostly still: they stay in).
      Stopwatch watch;
      const bool has_prior = !prior.masks.dynamic.empty();
      geometry = DetectGeometrically(has_prior ? frame.WithoutMasked(prior.masks.dynamic) : frame, depth,
                                     /*estimate_knows_movers=*/has_prior);
      timings_->Add("geometry", watch.ElapsedMs());
    }
    int movables_dropped = 0;
    removal.mask = dynamic::FuseDynamicMasks(prior.masks, geometry, Fusion(), &movables_dropped);
    // An overruled geometry dropped no movable segment either.
    const bool overruled = options_.mode == DynamicMode::kFull && !geometry.dynamic_mask.empty() &&
                           OverruleFailedGeometry(frame, prior, &removal.mask);
    if (!overruled) stats_.movable_segments_dropped += movables_dropped;
  }
  removal.keypoints = removal.mask.empty() ? std::vector<bool>(frame.size(), false) : frame.OnMask(removal.mask);
  removal.count = static_cast<std::size_t>(std::count(removal.keypoints.begin(), removal.keypoints.end(), true));
  stats_.keypoints_removed += static_cast<std::int64_t>(removal.count);
  removal.pixels = removal.mask.empty() ? 0 : static_cast<std::size_t>(cv::countNonZero(removal.mask));
  stats_.pixels_removed += static_cast<std::int64_t>(removal.pixels);
  stats_.pixels_total += static_cast<std::int64_t>(removal.mask.empty() ? depth.total() : removal.mask.total());
  if (!moving_truth.empty()) CountAgainstTruth(frame, removal.keypoints, moving_truth);
  return removal;
}

bool GeometryTakesTooMuch(const Frame& frame, const cv::Mat& prior_removal, const cv::Mat& fused, double max_share) {
  if (frame.size() == 0 || max_share >= 1) return false;
  const auto static_left = [&frame](const cv::Mat& mask) {
    if (mask.empty()) return static_cast<double>(frame.size());
    const std::vector<bool> on = frame.OnMask(mask);
    return static_cast<double>(std::count(on.begin(), on.end(), false));
  };
  const double left_by_prior = static_left(prior_removal);
  return left_by_prior - static_left(fused) > max_share * left_by_prior;
}

bool DynamicStage::OverruleFailedGeometry(const Frame& frame, const DynamicPrior& prior, cv::Mat* fused) {
  if (prior.masks.dynamic.empty() ||
      !GeometryTakesTooMuch(frame, prior.removal, *fused, options_.max_geometry_share_of_prior_static)) {
    return false;
  }
  *fused = prior.removal.empty() ? cv::Mat::zeros(fused->size(), CV_8UC1) : prior.removal.clone();
  ++stats_.geometry_overruled;
  return true;
}

dynamic::GeometryResult DynamicStage::DetectGeometrically(const Frame& frame, const cv::Mat& depth,
                                                          bool estimate_knows_movers) {
  DLSLAM_CHECK(depth.type() == CV_32FC1 && depth.cols == camera_.width && depth.rows == camera_.height,
               "depth must be float metres {}x{}", camera_.width, camera_.height);
  const std::optional<SE3d> cam_from_world = tracker_->EstimatePose(frame);
  if (!cam_from_world) return {};  // not tracking: no pose to project with
  const std::size_t n = static_cast<std::size_t>(options_.geometry.multiview.max_reference_views);
  std::vector<dynamic::ReferenceView> views;
  for (const KeyFrameSnapshot& kf : map_->GetCovisibleKeyFrames(tracker_->reference_keyframe(), n)) {
    views.push_back(MakeReferenceView(kf));
  }
  if (views.empty()) return {};
  dynamic::GeometryResult result =
      detector_.Detect(depth, camera_, *cam_from_world, views, MovedIn(depth, *cam_from_world, /*count=*/true));
  const auto share_of_image = [](const cv::Mat& mask) {
    return cv::countNonZero(mask) / static_cast<double>(mask.total());
  };
  const double share = share_of_image(result.dynamic_mask);
  if (options_.resolve_inverted_check && !estimate_knows_movers && share >= options_.inverted_check_min_share) {
    // Perhaps the estimate followed the movers, and what moves is the rest:
    // estimate again from the keypoints inside the "moving" region only,
    // and keep the labelling that leaves the larger part of the image static.
    const std::optional<SE3d> other = tracker_->EstimatePose(frame.Subset(frame.OnMask(result.dynamic_mask)));
    if (other) {
      dynamic::GeometryResult alternative =
          detector_.Detect(depth, camera_, *other, views, MovedIn(depth, *other, /*count=*/false));
      ++stats_.inverted_checks_tried;
      if (share_of_image(alternative.dynamic_mask) < share) {
        result = std::move(alternative);
        ++stats_.inverted_checks_resolved;
      }
    }
  }
  ++stats_.frames_with_geometry;
  stats_.keypoints_tested += result.points_tested;
  stats_.keypoints_dynamic += result.points_dynamic;
  if (options_.cull_vanished_points && !result.vanished_ids.empty()) {
    std::vector<MapPointId> doomed;
    for (std::uint64_t id : result.vanished_ids) {
      if (id != kNoId) doomed.push_back(id);
    }
    stats_.map_points_culled += map_->ErasePoints(doomed);
  }
  return result;
}

cv::Mat DynamicStage::MovedIn(const cv::Mat& depth, const SE3d& cam_from_world, bool count) {
  // Views from before a map correction are forgotten at the next OfferView.
  if (!options_.geometry.free_space.enabled || free_space_.views() == 0 ||
      map_->Generation() != free_space_generation_) {
    return {};
  }
  Stopwatch watch;
  dynamic::FreeSpaceStats stats;
  cv::Mat violations = free_space_.Violations(depth, cam_from_world, &stats);
  timings_->Add("free_space", watch.ElapsedMs());
  if (!count) return violations;
  ++stats_.free_space_frames;
  stats_.free_space_views_ignored += stats.views_ignored;
  if (!violations.empty()) {
    stats_.free_space_share_sum += cv::countNonZero(violations) / static_cast<double>(violations.total());
  }
  return violations;
}

void DynamicStage::OfferView(const cv::Mat& depth, const SE3d& cam_from_world) {
  if (!UsesGeometry(options_.mode) || !options_.geometry.free_space.enabled || depth.empty()) return;
  if (map_->Generation() != free_space_generation_) {
    free_space_.Reset();
    free_space_generation_ = map_->Generation();
  }
  free_space_.Offer(depth, cam_from_world);
}

void DynamicStage::CountAgainstTruth(const Frame& frame, const std::vector<bool>& removed_flags,
                                     const cv::Mat& truth) {
  DLSLAM_CHECK(truth.type() == CV_8UC1 && truth.cols == camera_.width && truth.rows == camera_.height,
               "the ground-truth mask must be 8-bit single-channel {}x{}", camera_.width, camera_.height);
  ++stats_.frames_with_truth;
  for (std::size_t i = 0; i < frame.size(); ++i) {
    const Eigen::Vector2f& uv = frame.keypoint(i).raw_uv;
    const int x = std::clamp(static_cast<int>(std::lround(uv.x())), 0, truth.cols - 1);
    const int y = std::clamp(static_cast<int>(std::lround(uv.y())), 0, truth.rows - 1);
    const bool moving = truth.at<uchar>(y, x) != 0;
    const bool removed = removed_flags[i];
    if (removed && moving) ++stats_.true_positives;
    if (removed && !moving) ++stats_.false_positives;
    if (!removed && moving) ++stats_.false_negatives;
  }
}

}  // namespace dlslam
