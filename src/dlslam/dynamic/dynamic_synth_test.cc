// Accuracy of the whole geometry check on rendered walking_xyz frames with
// ground-truth poses: reference keyframes from earlier frames' ORB keypoints
// with depth, the final mask scored over the current frame's ORB keypoints
// against the renderer's moving-surface mask.

#include <gtest/gtest.h>

#include "dlslam/dynamic/tools/keyframe_eval.h"

namespace dlslam::dynamic {
namespace {

TEST(GeometryOnSynth, WalkingXyzPrecisionAndRecall) {
  synth::SynthOptions synth_options;
  synth_options.preset = synth::Preset::kWalkingXyz;
  synth_options.frames = 50;
  const synth::SynthSequence sequence(synth_options);
  evaluation::SynthFrameCache cache(sequence);
  evaluation::SynthEvalOptions options;
  options.first_frame = 36;
  options.frames = 2;
  options.step = 12;  // frames 36 and 48; keyframes every 6 frames before each
  evaluation::SynthEvalStats stats[2];
  for (const SearchKind kind : {SearchKind::kExhaustive, SearchKind::kAntColony}) {
    GeometryOptions geometry;
    geometry.search = kind;
    evaluation::SynthEvalStats& s = stats[kind == SearchKind::kAntColony];
    s = evaluation::EvaluateOnSynth(cache, geometry, options);
    const evaluation::KeypointScores& k = s.scores;
    const long keypoints = k.true_positive + k.false_positive + k.false_negative + k.true_negative;
    const double base_rate = static_cast<double>(k.true_positive + k.false_negative) / keypoints;
    SCOPED_TRACE(ToString(kind));
    // Two walkers in view: a fair share of keypoints is on them, or the test
    // would measure nothing.
    ASSERT_GT(k.true_positive + k.false_negative, 40);
    // Recall: the people cross the view, so most of their keypoints see the
    // background behind them in some keyframe; region growing from the
    // dense dynamic points covers the body. Misses are thin limbs.
    EXPECT_GT(k.Recall(), 0.8);
    // Precision: the mask leaks onto surfaces the people touch (floor,
    // furniture; up to 40 px from a seed), but it must be far better than
    // chance (a mask of random pixels scores the base rate).
    EXPECT_GT(k.Precision(), 0.3);
    EXPECT_GT(k.Precision(), 2.0 * base_rate);
    // Most dynamic points lie on truly moving surfaces.
    EXPECT_GT(static_cast<double>(s.dynamic_on_movers) / static_cast<double>(s.points_dynamic), 0.75);
  }
  // The ant colony tests far fewer points for the same detections.
  EXPECT_EQ(stats[0].points_tested, stats[0].points_projected);
  EXPECT_LT(stats[1].points_tested, 0.75 * static_cast<double>(stats[1].points_projected));
  EXPECT_GT(stats[1].scores.Recall(), stats[0].scores.Recall() - 0.05);
}

}  // namespace
}  // namespace dlslam::dynamic
