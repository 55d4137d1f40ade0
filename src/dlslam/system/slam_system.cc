#include "dlslam/system/slam_system.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <numbers>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "dlslam/map/map_file.h"
#include "dlslam/place/vocabulary_file.h"
#include "dlslam/util/check.h"

namespace dlslam {

namespace {

std::unique_ptr<place::KeyFrameIndex> MakeKeyFrameIndex(const SystemOptions& options) {
  if (!options.relocalization && !options.loop_closing) return nullptr;
  const std::filesystem::path file = place::FindVocabulary(options.vocabulary);
  const Stopwatch watch;
  auto vocabulary = std::make_shared<const place::Vocabulary>(place::LoadVocabulary(file));
  spdlog::debug("vocabulary {}: {} words, loaded in {:.1f} ms", file.string(), vocabulary->word_count(),
                watch.ElapsedMs());
  // The direct index groups features by their node two levels below the
  // root; a vocabulary with one level (vocab train --levels 1) cannot.
  constexpr int kDirectIndexLevel = 2;
  if (vocabulary->levels() < kDirectIndexLevel) {
    throw InputError(file, 0, "vocabulary has {} level(s); relocalization and loop closing need at least {} "
                     "(vocab train --levels)", vocabulary->levels(), kDirectIndexLevel);
  }
  return std::make_unique<place::KeyFrameIndex>(std::move(vocabulary), kDirectIndexLevel);
}

TrackerOptions TrackerFor(const SystemOptions& options) {
  TrackerOptions tracker = options.tracker;
  if (options.localization_only) tracker.insert_keyframes = false;
  // Crowds need fresher keyframes; a static scene in mode orb would only
  // pay for them (TrackerOptions::max_frames_between_keyframes_dynamic).
  if (options.dynamic.mode != DynamicMode::kOrb) {
    tracker.max_frames_between_keyframes = tracker.max_frames_between_keyframes_dynamic;
  }
  // Without the network's masks the inliers of a gated solve may be people.
  if (!UsesSemanticPrior(options.dynamic.mode)) tracker.gated_keyframe_min_inliers = 0;
  return tracker;
}

bool SameCamera(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  const auto close = [](double x, double y) { return std::abs(x - y) <= 1e-9 * std::max(1.0, std::abs(x)); };
  return a.width == b.width && a.height == b.height && close(a.fx, b.fx) && close(a.fy, b.fy) &&
         close(a.cx, b.cx) && close(a.cy, b.cy) && close(a.k1, b.k1) && close(a.k2, b.k2) && close(a.p1, b.p1) &&
         close(a.p2, b.p2) && close(a.k3, b.k3) && close(a.bf, b.bf);
}

std::string Describe(const CameraIntrinsics& c) {
  return fmt::format("{} {}x{} fx {:.3f} fy {:.3f} cx {:.3f} cy {:.3f} k1 {:g} bf {:g}", Quoted(c.name), c.width,
                     c.height, c.fx, c.fy, c.cx, c.cy, c.k1, c.bf);
}

}  // namespace

void SlamSystem::LoadMap(const std::filesystem::path& file) {
  DLSLAM_CHECK(counts_.frames == 0 && map_.NumKeyFrames() == 0, "LoadMap before the first frame");
  const Stopwatch watch;
  Map loaded;
  const MapFileHeader header = dlslam::LoadMap(file, &loaded);
  if (!SameCamera(header.camera, camera_)) {
    throw InputError(file, 0, "the map was made with camera {}; this run's camera is {}", Describe(header.camera),
                     Describe(camera_));
  }
  if (header.pyramid.levels != pyramid_.levels || std::abs(header.pyramid.scale_factor - pyramid_.scale_factor) > 1e-12) {
    throw InputError(file, 0, "the map's keypoints come from an ORB pyramid of {} levels x {}; this run extracts {} x {}",
                     header.pyramid.levels, header.pyramid.scale_factor, pyramid_.levels, pyramid_.scale_factor);
  }
  map_.Import(loaded.Export());
  std::vector<KeyFramePose> keyframes = map_.KeyFramePoses();
  if (keyframes.empty()) throw InputError(file, 0, "the map has no keyframe");
  if (index_) {
    for (const KeyFramePose& k : keyframes) index_->Add(k.id, map_.GetKeyFrame(k.id)->frame->descriptors());
  }
  tracker_.StartInMap(keyframes.back().id);
  spdlog::info("loaded map {}: {} keyframes, {} map points in {:.0f} ms", file.string(), keyframes.size(),
               map_.NumMapPoints(), watch.ElapsedMs());
}

void SlamSystem::SaveMap(const std::filesystem::path& file) const {
  DLSLAM_CHECK(shut_down_, "SaveMap after Shutdown");
  dlslam::SaveMap(map_, {camera_, pyramid_}, file);
}

KeyFrameHooks SlamSystem::MappingHooks() {
  KeyFrameHooks hooks;
  if (place::KeyFrameIndex* index = index_.get()) {
    hooks.added = [index](const KeyFrameSnapshot& keyframe) { index->Add(keyframe.id, keyframe.frame->descriptors()); };
    hooks.culled = [index](KeyFrameId id) { index->Erase(id); };
  }
  if (options_.loop_closing) {
    // loop_closer_ is made after the mapper; keyframes only flow once both exist.
    hooks.processed = [this](KeyFrameId id) { loop_closer_->Enqueue(id); };
  }
  return hooks;
}

features::OrbOptions StaticOrbOptions() {
  features::OrbOptions options;
  options.fast_threshold_initial = 8;
  options.fast_threshold_min = 4;
  return options;
}

const char* ToString(PoseSource source) {
  switch (source) {
    case PoseSource::kTracked: return "tracked";
    case PoseSource::kRelocalized: return "relocalized";
    case PoseSource::kCoasted: return "coasted";
    case PoseSource::kNewMap: return "new_map";
    case PoseSource::kNone: return "none";
  }
  return "?";
}

void SystemOptions::Check() const {
  orb.Check();
  static_orb.Check();
  tracker.Check();
  mapping.Check();
  loop.Check();
  dynamic.Check();
  semantic.Check();
  DLSLAM_CHECK(reextract_removed_share > 0 && reextract_removed_share <= 1,
               "SystemOptions::reextract_removed_share {} outside (0, 1]", reextract_removed_share);
  DLSLAM_CHECK(static_orb_removed_share >= 0 && static_orb_removed_share <= 1,
               "SystemOptions::static_orb_removed_share {} outside [0, 1]", static_orb_removed_share);
  DLSLAM_CHECK(max_mapping_lag_frames >= 0, "SystemOptions::max_mapping_lag_frames {} must be >= 0",
               max_mapping_lag_frames);
  DLSLAM_CHECK(max_mapping_wait_ms >= 0 && max_mapping_wait_ms <= 60000,
               "SystemOptions::max_mapping_wait_ms {} outside [0, 60000]", max_mapping_wait_ms);
  DLSLAM_CHECK(merge_every_frames >= 1 && merge_every_frames <= 100000,
               "SystemOptions::merge_every_frames {} outside [1, 100000]", merge_every_frames);
  DLSLAM_CHECK(merge_agreement_m > 0 && merge_agreement_deg > 0,
               "SystemOptions::merge_agreement {} m, {} deg must be > 0", merge_agreement_m, merge_agreement_deg);
}

SlamSystem::SlamSystem(const CameraIntrinsics& camera, const SystemOptions& options)
    : camera_(camera),
      options_(options),
      extractor_(options.orb),
      static_extractor_(options.static_orb),
      pyramid_{options.orb.n_levels, options.orb.scale_factor},
      index_(MakeKeyFrameIndex(options)),
      tracker_(TrackerFor(options), &map_, options.relocalization ? index_.get() : nullptr),
      dynamic_(options.dynamic, camera, &map_, &tracker_, &timings_),
      mapper_(options.mapping, &map_, &timings_, MappingHooks()) {
  camera_.Check();
  options_.Check();
  if (options_.loop_closing) {
    loop_closer_ = std::make_unique<LoopCloser>(options_.loop, &map_, index_.get(), &mapper_, &timings_);
  }
  if (options_.semantic.network && UsesSemanticPrior(options_.dynamic.mode)) {
    semantic_ = std::make_unique<SemanticFeed>(options_.semantic, camera_, &timings_,
                                               [this] { return tracker_.PredictedCamFromWorld(); });
  }
  if (options_.sequential) return;
  tracker_.SetMappingBacklog([this] { return mapper_.backlog(); });
  mapper_.Start();
  if (loop_closer_) loop_closer_->Start();
}

SlamSystem::~SlamSystem() { Shutdown(); }

TrackingResult SlamSystem::TrackRgbd(const cv::Mat& colour, const cv::Mat& depth, double timestamp,
                                     const cv::Mat& semantic_prior) {
  DynamicInputs inputs;
  if (!semantic_prior.empty()) {
    inputs.semantic_prior = [&semantic_prior] { return dynamic::SemanticMasks{semantic_prior}; };
  }
  return TrackRgbd(colour, depth, timestamp, inputs);
}

TrackingResult SlamSystem::TrackRgbd(const cv::Mat& colour, const cv::Mat& depth, double timestamp,
                                     const DynamicInputs& dynamic) {
  DLSLAM_CHECK(!shut_down_, "the system was shut down");
  CheckColour(colour, timestamp);
  ++counts_.frames;
  Stopwatch total;
  frame_started_ = std::chrono::steady_clock::now();
  DynamicInputs inputs = dynamic;
  const long frame_id = counts_.frames;
  SemanticFeed::FrameMasks masks;
  if (semantic_ && !inputs.semantic_prior) {
    // Asynchronous masks once tracking runs (the first keyframe, the map's
    // foundation, waits for its own masks) and the view is not crowded.
    const bool crowded = last_removed_share_ >= options_.semantic.wait_when_removed_share ||
                         tracker_.state() != TrackingState::kOk;
    const bool carry = semantic_->asynchronous() && !crowded;
    if (carry) ReleaseHeldKeyFrame(/*wait=*/false);
    // Handed to the semantic thread before ORB extraction; the dynamic
    // stage waits for its own masks only after it.
    masks = semantic_->ForFrame(frame_id, colour, depth, timestamp, carry);
    counts_.frames_segmented_ahead += masks.segmented_ahead;
    inputs.semantic_prior = masks.prior;
  }
  BoundMappingLag(frame_id, timestamp);  // the network works on this frame meanwhile
  const DynamicPrior prior = dynamic_.TakePrior(inputs, depth);
  Stopwatch watch;
  const features::OrbExtractor* first = nullptr;
  const features::OrbFeatures features = ExtractOutside(colour, prior, &first);
  timings_.Add("orb_extraction", watch.ElapsedMs());
  auto frame = std::make_shared<Frame>(
      Frame::Create(timestamp, features.keypoints, features.descriptors, depth, camera_, pyramid_));
  const DynamicRemoval removal = dynamic_.Process(*frame, depth, prior, inputs.moving_truth);
  last_view_.removed.clear();
  for (std::size_t i = 0; i < removal.keypoints.size(); ++i) {
    if (removal.keypoints[i]) last_view_.removed.push_back(features.keypoints[i].pt);
  }
  last_view_.removed_mask = removal.mask;
  // The prior's part of what was removed: all of prior.removal when final,
  // else what the fusion kept of it (policy geometry keeps none).
  last_view_.prior_mask = prior.removal.empty() || removal.mask.empty() ? cv::Mat()
                          : prior.final                               ? prior.removal
                                                                      : (prior.removal & removal.mask);
  last_removed_share_ = removal.image_share();
  if (removal.count > 0) {
    // Tracking and mapping see only static keypoints: extracted again
    // outside the removed regions when many were removed, else the others.
    if (static_cast<double>(removal.count) >= options_.reextract_removed_share * static_cast<double>(frame->size())) {
      watch = Stopwatch();
      // After a first extraction with the same options only the spread and
      // the descriptors are redone (OrbExtractor::Reextract); else it runs on
      // the first extraction's pyramid, with static_orb's thresholds.
      const features::OrbFeatures statics =
          first == &static_extractor_              ? static_extractor_.Reextract(removal.mask)
          : static_extractor_.CanExtractOn(*first) ? static_extractor_.ExtractOn(*first, removal.mask)
                                                   : static_extractor_.Extract(colour, removal.mask);
      frame = std::make_shared<Frame>(
          Frame::Create(timestamp, statics.keypoints, statics.descriptors, depth, camera_, pyramid_));
      ++counts_.frames_reextracted;
      timings_.Add("orb_reextraction", watch.ElapsedMs());
    } else {
      std::vector<bool> keep = removal.keypoints;
      keep.flip();
      frame = std::make_shared<Frame>(frame->Subset(keep));
    }
  }
  last_view_.kept.clear();
  for (const FrameKeypoint& k : frame->keypoints()) last_view_.kept.emplace_back(k.raw_uv.x(), k.raw_uv.y());
  watch = Stopwatch();
  // A keyframe from carried masks waits for its own (ReleaseHeldKeyFrame).
  // A frame that waited for its own masks has the held keyframe's too (they
  // were queued before): it goes into the map before this frame is tracked.
  if (!masks.carried) ReleaseHeldKeyFrame(/*wait=*/true);
  TrackContext context;
  context.hold_keyframe = masks.carried && options_.semantic.keyframes_wait_for_own_masks;
  context.removed_share = removal.image_share();
  const TrackingResult result = tracker_.Track(frame, context);
  timings_.Add("tracking", watch.ElapsedMs());
  if (semantic_) semantic_->SetPose(frame_id, result.cam_from_world);
  // A gated pose disagreed with its own matches: not a view to test against.
  if (result.state == TrackingState::kOk && result.cam_from_world && !result.gated) {
    dynamic_.OfferView(depth, *result.cam_from_world);
  }
  if (result.held_keyframe && !held_keyframe_) {  // one at a time: a second one is simply not made
    HeldKeyFrame held;
    held.candidate = *result.held_keyframe;
    held.masks = masks.own ? *masks.own : semantic_->Segment(masks.image, frame_id);
    held.timestamp = timestamp;
    if (options_.keep_keyframe_images) {
      held.colour = colour.clone();
      held.depth = depth.clone();
      held.removed = removal.mask.clone();
    }
    held_keyframe_ = std::move(held);
    ++counts_.keyframes_held;
  }
  // Attempts on frames without features (black, covered) cost nothing and
  // would only pull the median down.
  if (result.relocalization_ms >= 0 && frame->size() > 0) {
    timings_.Add("relocalization_attempt", result.relocalization_ms);
  }
  LogStateChange(result, timestamp);
  if (spdlog::should_log(spdlog::level::debug)) {
    std::string where;
    if (result.cam_from_world) {
      const Eigen::Vector3d c = result.cam_from_world->Inverse().translation();
      where = fmt::format(", camera at ({:.3f}, {:.3f}, {:.3f})", c.x(), c.y(), c.z());
    }
    spdlog::debug("t={:.6f}: {} on {} keypoints, {} matches, {} inliers{}{}{}", timestamp, ToString(result.state),
                  frame->size(), result.matches, result.inliers, result.gated ? ", gated on the prediction" : "",
                  result.new_keyframe ? ", new keyframe" : "", where);
  }
  if (result.new_map) {
    ++counts_.maps_started;
    frames_in_new_map_ = 0;
    pending_merge_.reset();
    spdlog::info("t={:.6f}: lost for too long, a new map starts at the last pose (keyframe {})", timestamp,
                 result.reference_keyframe);
  } else if (result.state == TrackingState::kOk && tracker_.new_map_origin()) {
    TryMergeNewMap(*frame, result);
  }
  counts_.frames_gated += result.gated;
  if (result.jump_refused) {
    ++counts_.jumps_refused;
    spdlog::debug("t={:.6f}: tracked pose refused, too far from the motion model", timestamp);
  }
  if (result.new_keyframe) KeyFrameMade(result.reference_keyframe, timestamp, colour, depth, removal.mask);
  PoseSource source = PoseSource::kNone;
  switch (result.state) {
    case TrackingState::kOk:
      ++counts_.frames_tracked;
      if (result.relocalized) {
        source = PoseSource::kRelocalized;
      } else if (tracker_.new_map_origin()) {
        source = PoseSource::kNewMap;
        ++counts_.frames_new_map;
      } else {
        source = PoseSource::kTracked;
      }
      break;
    case TrackingState::kCoasting:
      ++counts_.frames_coasted;
      source = PoseSource::kCoasted;
      break;
    case TrackingState::kLost: ++counts_.frames_lost; break;
    case TrackingState::kNotInitialized: ++counts_.frames_waiting; break;
  }
  if (source != PoseSource::kNone) {
    tracked_.push_back({timestamp, result.reference_keyframe, result.cam_from_reference});
  }
  sources_.push_back({timestamp, source});
  timings_.Add("frame_total", total.ElapsedMs());
  return result;
}

features::OrbFeatures SlamSystem::ExtractOutside(const cv::Mat& colour, const DynamicPrior& prior,
                                                 const features::OrbExtractor** used) {
  *used = &extractor_;
  if (!options_.extract_outside_prior || !prior.final || prior.removal.empty()) return extractor_.Extract(colour);
  ++counts_.frames_extracted_outside_prior;
  const bool crowded = prior.removed_share() >= options_.static_orb_removed_share;
  features::OrbExtractor& extractor = crowded ? static_extractor_ : extractor_;
  *used = &extractor;
  return extractor.Extract(colour, prior.removal);
}

void SlamSystem::CheckColour(const cv::Mat& colour, double timestamp) const {
  DLSLAM_CHECK(!colour.empty(), "empty colour image at t={:.6f}", timestamp);
  DLSLAM_CHECK(colour.cols == camera_.width && colour.rows == camera_.height,
               "colour image at t={:.6f} is {}x{}, camera is {}x{}", timestamp, colour.cols, colour.rows,
               camera_.width, camera_.height);
}

void SlamSystem::SegmentAhead(const cv::Mat& colour, double timestamp) {
  DLSLAM_CHECK(!shut_down_, "the system was shut down");
  if (!semantic_) return;
  CheckColour(colour, timestamp);
  semantic_->SegmentAhead(colour, timestamp);
}

void SlamSystem::KeyFrameMade(KeyFrameId id, double timestamp, const cv::Mat& colour, const cv::Mat& depth,
                              const cv::Mat& removed) {
  if (options_.keep_keyframe_images) KeepKeyFrameImages(id, timestamp, colour, depth, removed);
  const Stopwatch watch;
  const std::uint64_t ticket = mapper_.Enqueue(id);  // blocks only while the queue is full
  if (!options_.sequential && options_.max_mapping_lag_frames > 0) {
    unmapped_.push_back({counts_.frames, timestamp, frame_started_, ticket});
  }
  timings_.Add("keyframe_handover", watch.ElapsedMs());
}

void SlamSystem::BoundMappingLag(long frame_id, double timestamp) {
  if (options_.sequential || options_.max_mapping_lag_frames <= 0) return;
  const Stopwatch watch;
  while (!unmapped_.empty() && frame_id - unmapped_.front().frame >= options_.max_mapping_lag_frames) {
    const UnmappedKeyFrame& keyframe = unmapped_.front();
    // Only time the camera would have left: frames played faster than their
    // timestamps (a live camera paces them itself). A loop correction pauses
    // local mapping for longer than the bound: tracking goes on then.
    const double camera_ms = (timestamp - keyframe.timestamp) * 1e3;
    const double spent_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - keyframe.frame_started).count();
    const double wait_ms = std::min<double>(options_.max_mapping_wait_ms, camera_ms - spent_ms);
    if (wait_ms > 0) {
      mapper_.WaitForProcessed(keyframe.ticket, std::chrono::microseconds(std::lround(wait_ms * 1e3)));
    }
    unmapped_.pop_front();
  }
  timings_.Add("mapping_wait", watch.ElapsedMs());
}

void SlamSystem::ReleaseHeldKeyFrame(bool wait) {
  if (!held_keyframe_) return;
  HeldKeyFrame& held = *held_keyframe_;
  const bool ready = held.masks.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  if (!ready && !wait && held.frames_waited < options_.semantic.keyframe_mask_max_wait_frames) {
    ++held.frames_waited;
    return;
  }
  if (!ready) {
    const Stopwatch watch;
    held.masks.wait();
    timings_.Add("keyframe_mask_wait", watch.ElapsedMs());
  }
  // Taken out of the slot first: a segmentation error propagates (as a
  // frame's own would) and leaves no keyframe behind.
  const HeldKeyFrame taken = std::move(*held_keyframe_);
  held_keyframe_.reset();
  const cv::Mat& mask = taken.masks.get().dynamic_mask;
  std::vector<bool> keep(taken.candidate.frame->size(), true);
  if (!mask.empty()) {
    keep = taken.candidate.frame->OnMask(mask);
    keep.flip();
  }
  counts_.keyframe_keypoints_masked_late += std::count(keep.begin(), keep.end(), false);
  const std::optional<KeyFrameId> id = tracker_.InsertHeldKeyFrame(taken.candidate, keep);
  if (!id) {
    ++counts_.keyframes_held_dropped;
    return;
  }
  // The dense map leaves out what either removed (the keyframe's own copy).
  cv::Mat removed = taken.removed;
  if (removed.empty()) {
    removed = mask;
  } else if (!mask.empty()) {
    removed |= mask;
  }
  KeyFrameMade(*id, taken.timestamp, taken.colour, taken.depth, removed);
}

void SlamSystem::TryMergeNewMap(const Frame& frame, const TrackingResult& result) {
  if (++frames_in_new_map_ % options_.merge_every_frames != 0 || !result.cam_from_world) return;
  const Stopwatch watch;
  const std::optional<Relocalization> found = tracker_.FindInOlderMaps(frame);
  timings_.Add("merge_attempt", watch.ElapsedMs());
  if (!found) return;
  const KeyFrameId origin = *tracker_.new_map_origin();
  // cam_from_old_world = cam_from_new_world * new_world_from_old_world.
  const SE3d new_from_old = result.cam_from_world->Inverse() * found->cam_from_world;
  // One relocalization may be wrong (a kitchen has many similar cupboards)
  // and a wrong merge wrecks both maps: two in a row must agree.
  const std::optional<SE3d> previous = std::exchange(pending_merge_, new_from_old);
  if (!previous) return;
  const SE3d disagreement = *previous * new_from_old.Inverse();
  constexpr double kRadToDeg = 180.0 / std::numbers::pi;
  if (disagreement.translation().norm() > options_.merge_agreement_m ||
      disagreement.so3().Log().norm() * kRadToDeg > options_.merge_agreement_deg) {
    return;
  }
  {
    const PauseGate::Hold paused = mapper_.Pause();  // its bundle would write back poses from before
    std::unordered_map<KeyFrameId, SE3d> corrected;
    for (const KeyFramePose& k : map_.KeyFramePoses()) {
      if (k.id >= origin) corrected.emplace(k.id, k.cam_from_world * new_from_old);
    }
    map_.ApplyCorrectedPoses(corrected);
  }
  tracker_.MergedIntoOlderMap(*found);
  pending_merge_.reset();
  ++counts_.maps_merged;
  spdlog::info("t={:.6f}: the map started at keyframe {} merged into the older map at keyframe {} ({} inliers; "
               "moved {:.3f} m, {:.2f} deg)", frame.timestamp(), origin, found->keyframe, found->inliers,
               new_from_old.translation().norm(), new_from_old.so3().Log().norm() * kRadToDeg);
}

void SlamSystem::LogStateChange(const TrackingResult& result, double timestamp) {
  if (result.relocalized) {
    ++counts_.relocalizations;
    spdlog::debug("t={:.6f}: lost -> relocalized on keyframe {} ({} inliers)", timestamp,
                 result.relocalization_keyframe, result.inliers);
  } else if (result.state != last_state_ && last_state_ != TrackingState::kNotInitialized) {
    spdlog::debug("t={:.6f}: {} -> {}", timestamp, ToString(last_state_), ToString(result.state));
  }
  if (result.state != TrackingState::kNotInitialized) last_state_ = result.state;
}

void SlamSystem::MarkLost(double timestamp) {
  ++counts_.frames;
  ++counts_.frames_lost;
  sources_.push_back({timestamp, PoseSource::kNone});
  if (last_state_ == TrackingState::kOk || last_state_ == TrackingState::kCoasting) {
    spdlog::debug("t={:.6f}: {} -> lost (frame unreadable)", timestamp, ToString(last_state_));
  }
  if (last_state_ != TrackingState::kNotInitialized) last_state_ = TrackingState::kLost;
}

void SlamSystem::MarkDropped(double timestamp) {
  ++counts_.frames;
  ++counts_.frames_dropped;
  sources_.push_back({timestamp, PoseSource::kNone});
}

void SlamSystem::KeepKeyFrameImages(KeyFrameId id, double timestamp, const cv::Mat& colour, const cv::Mat& depth,
                                    const cv::Mat& removed) {
  // Forget culled keyframes first (local mapping culls in its thread).
  std::vector<KeyFrameId> alive;
  for (const KeyFramePose& k : map_.KeyFramePoses()) alive.push_back(k.id);
  std::erase_if(keyframe_images_, [&](const auto& entry) {
    return !std::binary_search(alive.begin(), alive.end(), entry.first);
  });
  KeyFrameImages images;
  images.timestamp = timestamp;
  if (colour.type() == CV_8UC1) {
    cv::cvtColor(colour, images.colour, cv::COLOR_GRAY2BGR);
  } else {
    images.colour = colour.clone();
  }
  if (depth.empty()) {
    images.depth_mm = cv::Mat(colour.size(), CV_16UC1, cv::Scalar(0));
  } else {
    cv::Mat metres = depth.clone();
    cv::patchNaNs(metres, 0.0);
    metres.convertTo(images.depth_mm, CV_16UC1, 1000.0);  // saturates beyond 65 m
  }
  if (!removed.empty()) images.removed = removed.clone();
  keyframe_images_[id] = std::move(images);
}

dense::TsdfVolume SlamSystem::FuseDenseMap(const dense::TsdfOptions& options, const std::function<cv::Mat(double)>& tag,
                                           bool leave_out_removed) const {
  DLSLAM_CHECK(options_.keep_keyframe_images, "the dense map needs SystemOptions::keep_keyframe_images");
  dense::TsdfVolume volume(camera_, options);
  for (const KeyFramePose& k : map_.KeyFramePoses()) {
    const auto it = keyframe_images_.find(k.id);
    if (it == keyframe_images_.end()) continue;
    const KeyFrameImages& images = it->second;
    cv::Mat depth;
    images.depth_mm.convertTo(depth, CV_32FC1, 1e-3);
    volume.Integrate(k.cam_from_world, depth, images.colour, leave_out_removed ? images.removed : cv::Mat(),
                     tag ? tag(images.timestamp) : cv::Mat());
  }
  return volume;
}

void SlamSystem::Shutdown() {
  if (shut_down_) return;
  try {
    ReleaseHeldKeyFrame(/*wait=*/true);  // the last keyframe belongs in the map
  } catch (const std::exception& e) {
    spdlog::warn("the last keyframe is left out of the map: its segmentation failed: {}", e.what());
  }
  if (semantic_) semantic_->Stop();
  mapper_.Stop();
  if (loop_closer_) loop_closer_->Stop();
  shut_down_ = true;
}

Trajectory SlamSystem::CameraTrajectory() const {
  Trajectory out;
  out.reserve(tracked_.size());
  for (const FrameRecord& r : tracked_) {
    const auto reference_pose = map_.ResolveCamFromWorld(r.reference);
    if (!reference_pose) continue;
    out.emplace_back(r.timestamp, (r.cam_from_reference * *reference_pose).Inverse());
  }
  return out;
}

Trajectory SlamSystem::KeyFrameTrajectory() const {
  Trajectory out;
  for (const KeyFramePose& k : map_.KeyFramePoses()) out.emplace_back(k.timestamp, k.cam_from_world.Inverse());
  return out;
}

std::vector<Eigen::Vector3d> SlamSystem::MapPointPositions() const { return map_.PointPositions(); }

RunStats SlamSystem::Stats() const {
  RunStats s = counts_;
  s.keyframes = map_.NumKeyFrames();
  s.map_points = map_.NumMapPoints();
  s.mapping = mapper_.stats();
  if (loop_closer_) s.loop = loop_closer_->stats();
  s.dynamic = dynamic_.stats();
  s.timing_ms = timings_.Summaries();
  return s;
}

}  // namespace dlslam
