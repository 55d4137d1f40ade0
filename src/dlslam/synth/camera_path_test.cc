#include "dlslam/synth/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dlslam/io/text_table.h"
#include "dlslam/synth/renderer.h"
#include "dlslam/synth/random.h"
#include "dlslam/synth/scene.h"
#include "tests/support/test_data.h"

namespace dlslam::synth {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double Angle(const SE3d& pose) { return pose.so3().Log().norm(); }

// Extent of a preset's motion over a minute, sampled at 10 Hz.
void MotionRange(Preset preset, double& max_translation, double& max_angle) {
  const CameraMotion motion(preset, 3);
  max_translation = max_angle = 0;
  for (double t = 0; t < 60; t += 0.1) {
    const SE3d pose = motion.FirstFromCam(t);
    max_translation = std::max(max_translation, pose.translation().norm());
    max_angle = std::max(max_angle, Angle(pose));
  }
}

TEST(CameraMotion, StartsAtTheFirstPose) {
  for (const std::string& name : PresetNames()) {
    const SE3d first = CameraMotion(ParsePreset(name), 9).FirstFromCam(0.0);
    EXPECT_LT(first.translation().norm(), 1e-12) << name;
    EXPECT_LT(Angle(first), 1e-12) << name;
  }
}

TEST(CameraMotion, PresetsMoveLikeTheirTumNamesakes) {
  double translation = 0, angle = 0;
  MotionRange(Preset::kWalkingXyz, translation, angle);  // ~+-0.5 m, small rotation
  EXPECT_GT(translation, 0.3);
  EXPECT_LT(translation, 0.6);
  EXPECT_LT(angle, 12 * kDeg);  // TUM walking_xyz: up to 18 deg
  MotionRange(Preset::kWalkingRpy, translation, angle);  // ~+-20-30 deg, fixed position
  EXPECT_GT(angle, 20 * kDeg);
  EXPECT_LT(angle, 35 * kDeg);
  EXPECT_LT(translation, 0.06);
  MotionRange(Preset::kWalkingStatic, translation, angle);  // sub-cm jitter
  EXPECT_LT(translation, 0.01);
  EXPECT_LT(angle, 0.5 * kDeg);
  MotionRange(Preset::kSittingStatic, translation, angle);
  EXPECT_LT(translation, 0.01);
  // Half sphere: 1 m diameter around a point 0.5 m ahead, looking at the scene.
  const CameraMotion half(Preset::kWalkingHalfsphere, 3);
  double farthest = 0;
  for (double t = 0; t < 60; t += 0.1) {
    const SE3d pose = half.FirstFromCam(t);
    EXPECT_NEAR((pose.translation() - Eigen::Vector3d(0, 0, 0.5)).norm(), 0.5, 0.02) << t;
    EXPECT_LE(pose.translation().z(), 0.52) << "stays on the near half";
    farthest = std::max(farthest, pose.translation().norm());
    // The optical axis points at the scene: the target 2.5 m ahead is near the image centre.
    const Eigen::Vector3d target_cam = pose.Inverse() * Eigen::Vector3d(0, 0, 2.5);
    EXPECT_LT(std::atan2(target_cam.head<2>().norm(), target_cam.z()), 3 * kDeg);
  }
  EXPECT_GT(farthest, 0.55);
}

TEST(CameraMotion, KidnapReappearsWhereItWas) {
  const CameraMotion motion(Preset::kKidnap, 5);
  const double resume = kKidnapMappingS + kKidnapCoveredS;
  // The pan moves (so there is a map to come back to) ...
  EXPECT_GT((motion.FirstFromCam(kKidnapMappingS).translation() - motion.FirstFromCam(0).translation()).norm(), 0.2);
  // ... and after the covered stretch it replays from the resume pose, up to
  // the hand tremor (a few mm, a fraction of a degree).
  for (double dt = 0; dt < 1.0; dt += 0.1) {
    const SE3d again = motion.FirstFromCam(resume + dt);
    const SE3d before = motion.FirstFromCam(kKidnapResumeAtS + dt);
    EXPECT_LT((again.translation() - before.translation()).norm(), 0.015) << dt;
    EXPECT_LT(Angle(again.Inverse() * before), 1.5 * kDeg) << dt;
  }
  EXPECT_FALSE(LensCovered(Preset::kKidnap, kKidnapMappingS - 0.01));
  EXPECT_TRUE(LensCovered(Preset::kKidnap, kKidnapMappingS));
  EXPECT_TRUE(LensCovered(Preset::kKidnap, resume - 0.01));
  EXPECT_FALSE(LensCovered(Preset::kKidnap, resume));
  EXPECT_FALSE(LensCovered(Preset::kStatic, kKidnapMappingS + 0.1));
}

TEST(CameraPath, PresetPathsStayInTheRoom) {
  const Scene scene = BuildScene(Preset::kStatic, 1);  // every preset shares the room layout
  for (const std::string& name : PresetNames()) {
    const Preset preset = ParsePreset(name);
    const Trajectory path = PresetCameraPath(preset, 4, PresetViewpoint(preset), 1800, 30.0, 1700000000.0);
    ASSERT_EQ(path.size(), 1800u);
    EXPECT_DOUBLE_EQ(path[1].timestamp, 1700000000.033333);
    for (const StampedPose& p : path) ASSERT_TRUE(InFreeSpace(scene, p.translation, 0.1)) << name << " " << p.timestamp;
  }
}

// Constant velocity screw: rotation about a fixed axis at a constant rate and
// translation linear in time, which slerp + linear interpolation reproduce exactly.
SE3d Screw(double t) {
  return SE3d(SO3d::Exp(Eigen::Vector3d(0.1, -0.3, 0.2) * t), Eigen::Vector3d(1.0, -2.0, 0.5) + Eigen::Vector3d(0.3, 0.1, -0.2) * t);
}

Trajectory ScrewTrajectory(double t0, double t1, double rate) {
  Trajectory gt;
  for (int k = 0; t0 + k / rate <= t1; ++k) gt.emplace_back(t0 + k / rate, Screw(t0 + k / rate));
  return gt;
}

TEST(CameraPath, InterpolationIsExactForAConstantScrew) {
  const Trajectory gt = ScrewTrajectory(100.0, 103.0, 100.0);
  for (const double t : {100.0, 100.004, 101.2345, 102.99, gt.back().timestamp}) {
    const std::optional<SE3d> pose = InterpolatePose(gt, t);
    ASSERT_TRUE(pose) << t;
    EXPECT_LT((pose->translation() - Screw(t).translation()).norm(), 1e-9) << t;
    EXPECT_LT(Angle(pose->Inverse() * Screw(t)), 1e-9) << t;
  }
  EXPECT_FALSE(InterpolatePose(gt, 99.999));
  EXPECT_FALSE(InterpolatePose(gt, gt.back().timestamp + 1e-4));
  EXPECT_FALSE(InterpolatePose({}, 100.0));
}

TEST(CameraPath, ReplayFollowsTheTrajectoryAndDropsFramesOutsideIt) {
  const Trajectory gt = ScrewTrajectory(100.0, 104.0, 100.0);
  std::vector<double> times;
  for (double t = 99.9; t < 104.2; t += 0.0331) times.push_back(t);
  const SE3d viewpoint(SO3d::Exp(Eigen::Vector3d(0.2, 0.1, -0.3)), Eigen::Vector3d(0.5, 0.0, 1.4));
  const ReplayPath replay = ReplayCameraPath(gt, times, viewpoint);
  EXPECT_EQ(replay.dropped_before, 4);  // 99.9 .. 99.9993
  EXPECT_GT(replay.dropped_after, 0);
  ASSERT_EQ(static_cast<int>(replay.path.size()) + replay.dropped_before + replay.dropped_after,
            static_cast<int>(times.size()));
  const Trajectory& path = replay.path;
  EXPECT_LT((path[0].world_from_cam().translation() - viewpoint.translation()).norm(), 1e-12);
  EXPECT_LT(Angle(path[0].world_from_cam().Inverse() * viewpoint), 1e-12);
  // Relative motion between any two frames equals the trajectory's at those times.
  for (std::size_t i = 0; i < path.size(); i += 7) {
    for (std::size_t j = i + 1; j < path.size(); j += 11) {
      const SE3d ours = path[i].world_from_cam().Inverse() * path[j].world_from_cam();
      const SE3d truth = Screw(path[i].timestamp).Inverse() * Screw(path[j].timestamp);
      EXPECT_LT((ours.translation() - truth.translation()).norm(), 1e-9);
      EXPECT_LT(Angle(ours.Inverse() * truth), 1e-9);
    }
  }
  // Without frame times: 30 Hz from the trajectory's start.
  const ReplayPath regular = ReplayCameraPath(gt, {}, viewpoint);
  EXPECT_EQ(regular.path.size(), 121u);
  EXPECT_DOUBLE_EQ(regular.path[30].timestamp, 101.0);
}

// TUM's ground truth repeats a timestamp now and then (fr3/walking_static
// line 2458, fr2/xyz 8 times), which io::ReadTumTrajectory refuses; this
// keeps the first of each.
Trajectory ReadGroundTruth(const std::filesystem::path& path) {
  Trajectory gt;
  for (const io::TextRow& row : io::ReadTextTable(path).rows) {
    double v[8];
    for (int i = 0; i < 8; ++i) v[i] = io::ParseDouble(row.fields.at(static_cast<std::size_t>(i)), path, row.line, "value");
    if (!gt.empty() && v[0] <= gt.back().timestamp) continue;
    gt.emplace_back(v[0], SE3d(Eigen::Quaterniond(v[7], v[4], v[5], v[6]), Eigen::Vector3d(v[1], v[2], v[3])));
  }
  return gt;
}

// The five TUM fr3 dynamic sequences replayed in our room: the camera stays in
// the free space and sees the textured room (valid depth over most of the image).
TEST(CameraPath, ReplayedTumSequencesStayInTheRoom) {
  DLSLAM_REQUIRE_SHARED_DATA(tum, "tum/gt");
  const Scene scene = BuildScene(Preset::kStatic, 2);
  const CameraIntrinsics camera = CameraPreset("freiburg3");
  RenderOptions render;
  render.depth.enabled = false;
  for (const std::string name : {"walking_xyz", "walking_static", "walking_rpy", "walking_halfsphere", "sitting_static"}) {
    const std::string file = "rgbd_dataset_freiburg3_" + name + ".txt";
    const Trajectory gt = ReadGroundTruth(tum / file);
    std::vector<double> times;
    for (const io::TextRow& row : io::ReadTextTable(tum.parent_path() / "associations" / file).rows) {
      times.push_back(io::ParseDouble(row.fields[0], file, row.line, "t"));
    }
    const ReplayPath replay = ReplayCameraPath(gt, times, scene.viewpoint);
    EXPECT_GT(replay.path.size(), 0.95 * static_cast<double>(times.size())) << name;
    for (const StampedPose& p : replay.path) {
      ASSERT_TRUE(InFreeSpace(scene, p.translation, 0.1)) << name << " at " << p.timestamp;
    }
    for (std::size_t i = 0; i < replay.path.size(); i += 300) {
      std::mt19937 rng(1);
      const RenderedFrame f = RenderFrame(scene, camera, {replay.path[i].world_from_cam(), 0.0}, render, rng);
      cv::Mat in_range = (f.true_depth > 0.4) & (f.true_depth < 4.0);
      EXPECT_GT(cv::countNonZero(in_range), 0.6 * 640 * 480) << name << " frame " << i;
    }
  }
}

}  // namespace
}  // namespace dlslam::synth
