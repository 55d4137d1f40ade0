// The loop preset (issue 4): the camera circles the room twice looking
// outward, so the second lap starts by seeing again what the first lap saw
// first, after the whole room in between.

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "dlslam/synth/camera_path.h"
#include "dlslam/synth/room.h"
#include "dlslam/synth/scene.h"
#include "dlslam/synth/sequence.h"

namespace dlslam::synth {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kFps = 30.0;
const int kLapFrames = static_cast<int>(std::lround(kLoopLapS * kFps));

Trajectory LoopPath(std::uint32_t seed) {
  return PresetCameraPath(Preset::kLoop, seed, PresetViewpoint(Preset::kLoop), PresetDefaultFrames(Preset::kLoop, kFps),
                          kFps, 0.0);
}

double Angle(const SE3d& pose) { return pose.so3().Log().norm(); }
Eigen::Vector3d Forward(const StampedPose& p) { return p.world_from_cam().so3().matrix().col(2); }
double Heading(const StampedPose& p) { return std::atan2(Forward(p).y(), Forward(p).x()); }

TEST(LoopPreset, DefaultIsTwoLapsAndAShortOverlap) {
  EXPECT_EQ(PresetDefaultFrames(Preset::kStatic, kFps), 300);
  const double seconds = PresetDefaultFrames(Preset::kLoop, kFps) / kFps;
  EXPECT_GE(seconds, 2 * kLoopLapS + 1.0);
  EXPECT_LE(seconds, 2 * kLoopLapS + 2.0);
  EXPECT_GE(kLoopLapS, 12.0);  // slow enough to track (see SpeedsStayTrackable)
  EXPECT_LE(kLoopLapS, 20.0);
}

// The second lap's start retraces the first lap's, up to the hand tremor
// (which does not repeat with the lap), while half a lap away the camera is
// across the circle looking the other way.
TEST(LoopPreset, SecondLapRetracesTheFirst) {
  for (const std::uint32_t seed : {1u, 7u}) {
    const Trajectory path = LoopPath(seed);
    ASSERT_GE(static_cast<int>(path.size()), kLapFrames + 30);
    for (std::size_t i = 0; i + static_cast<std::size_t>(kLapFrames) < path.size(); ++i) {
      const SE3d first = path[i].world_from_cam(), again = path[i + static_cast<std::size_t>(kLapFrames)].world_from_cam();
      ASSERT_LT((again.translation() - first.translation()).norm(), 0.03) << seed << " frame " << i;
      ASSERT_LT(Angle(first.Inverse() * again), 2.0 * kDeg) << seed << " frame " << i;
    }
    const SE3d start = path[0].world_from_cam(), half = path[static_cast<std::size_t>(kLapFrames / 2)].world_from_cam();
    EXPECT_NEAR((half.translation() - start.translation()).norm(), 2 * room::kLoopRadius, 0.05);
    EXPECT_GT(Angle(start.Inverse() * half), 170 * kDeg);
  }
}

// A horizontal circle at the viewpoint's height, looking radially outward
// with the viewpoint's pitch (the pitch must not tilt the circle).
TEST(LoopPreset, CirclesHorizontallyLookingOutward) {
  const Trajectory path = LoopPath(3);
  const Eigen::Vector2d centre = room::kLoopCentre;
  for (const StampedPose& p : path) {
    const Eigen::Vector2d radial = p.translation.head<2>() - centre;
    ASSERT_NEAR(radial.norm(), room::kLoopRadius, 0.03) << p.timestamp;
    ASSERT_NEAR(p.translation.z(), room::kViewpoint.z(), 0.03) << p.timestamp;
    const Eigen::Vector3d forward = Forward(p);
    ASSERT_LT(std::acos(std::clamp(radial.normalized().dot(forward.head<2>().normalized()), -1.0, 1.0)), 3 * kDeg)
        << p.timestamp;
    ASSERT_NEAR(std::asin(-forward.z()), room::kViewpointPitchDown, 1.5 * kDeg) << p.timestamp;
  }
}

// The heading, unwrapped frame by frame, turns 720 degrees over two laps
// and on through the overlap, always the same way.
TEST(LoopPreset, TurnsTwiceRound) {
  const Trajectory path = LoopPath(2);
  double turned = 0, at_two_laps = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double step = std::remainder(Heading(path[i]) - Heading(path[i - 1]), 2 * kPi);
    ASSERT_LT(step, 0.0) << "turns right (clockwise seen from above) at frame " << i;
    turned += step;
    if (static_cast<int>(i) == 2 * kLapFrames) at_two_laps = turned;
  }
  EXPECT_NEAR(at_two_laps, -4 * kPi, 2 * kDeg);
  const double overlap = 2 * kPi * (static_cast<double>(path.size() - 1) / kFps - 2 * kLoopLapS) / kLoopLapS;
  EXPECT_NEAR(turned, -4 * kPi - overlap, 2 * kDeg);
}

// Fastest frame-to-frame rates of a path [m/s, rad/s].
void PeakRates(const Trajectory& path, double& speed, double& turn_rate) {
  speed = turn_rate = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const double dt = path[i].timestamp - path[i - 1].timestamp;
    const SE3d step = path[i - 1].world_from_cam().Inverse() * path[i].world_from_cam();
    speed = std::max(speed, step.translation().norm() / dt);
    turn_rate = std::max(turn_rate, Angle(step) / dt);
  }
}

// No faster than the presets the tracker already follows: it turns at most
// as fast as walking_rpy and moves at a walking camera's pace.
TEST(LoopPreset, SpeedsStayTrackable) {
  const Trajectory loop = LoopPath(4);
  double speed = 0, turn_rate = 0, rpy_speed = 0, rpy_turn_rate = 0;
  PeakRates(loop, speed, turn_rate);
  PeakRates(PresetCameraPath(Preset::kWalkingRpy, 4, PresetViewpoint(Preset::kWalkingRpy), 1200, kFps, 0.0), rpy_speed,
            rpy_turn_rate);
  EXPECT_LT(turn_rate, rpy_turn_rate);
  EXPECT_LT(turn_rate, 30 * kDeg);
  EXPECT_LT(speed, 0.5);
  EXPECT_GT(speed, 2 * kPi * room::kLoopRadius / kLoopLapS);  // it keeps going round
}

// Every direction sees textured structure in the sensor's range: most of the
// image between 0.4 and 4 m, and ORB corners all over it (as
// Renderer.TypicalFramesAreRichInOrbFeatures asks of the other presets).
TEST(LoopPreset, SeesTexturedWallsAllAround) {
  SynthOptions options;
  options.preset = Preset::kLoop;
  options.frames = kLapFrames;
  options.render.depth.enabled = false;
  const SynthSequence sequence(options);
  EXPECT_EQ(sequence.frames_outside_free_space(), 0);
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(2000);
  for (int i = 0; i < kLapFrames; i += kLapFrames / 12) {
    const RenderedFrame frame = sequence.Render(i);
    const cv::Mat in_range = (frame.true_depth > 0.4) & (frame.true_depth < 4.0);
    EXPECT_GT(cv::countNonZero(in_range), 0.9 * frame.true_depth.total()) << "frame " << i;
    cv::Mat grey;
    cv::cvtColor(frame.colour, grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::KeyPoint> keypoints;
    orb->detect(grey, keypoints);
    int cells[16] = {};
    for (const auto& k : keypoints) ++cells[static_cast<int>(k.pt.y / 120) * 4 + static_cast<int>(k.pt.x / 160)];
    const auto covered = std::count_if(std::begin(cells), std::end(cells), [](int n) { return n >= 5; });
    EXPECT_GE(keypoints.size(), 500u) << "frame " << i;
    EXPECT_GE(covered, 12) << "frame " << i;
  }
}

}  // namespace
}  // namespace dlslam::synth
