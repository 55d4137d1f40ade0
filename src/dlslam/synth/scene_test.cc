#include "dlslam/synth/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dlslam/io/text_table.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/synth/camera_path.h"
#include "dlslam/synth/renderer.h"
#include "dlslam/synth/room.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::synth {
namespace {

SynthOptions Options(Preset preset, int frames) {
  SynthOptions o;
  o.preset = preset;
  o.frames = frames;
  o.seed = 4;
  return o;
}

// Largest displacement of any part's origin between t - dt and t.
double ActorMotion(const Actor& actor, double t, double dt = 1.0 / 30.0) {
  const auto now = actor.pose_at(t), before = actor.pose_at(t - dt);
  double worst = 0;
  for (std::size_t k = 0; k < now.size(); ++k) worst = std::max(worst, (now[k].translation() - before[k].translation()).norm());
  return worst;
}

struct MaskCounts {
  int person = 0, person_moving = 0, movable = 0, movable_moving = 0;
};

MaskCounts Count(const cv::Mat& mask) {
  MaskCounts c;
  for (auto it = mask.begin<std::uint8_t>(); it != mask.end<std::uint8_t>(); ++it) {
    const int cls = MaskClass(*it);
    EXPECT_LE(cls, 2);
    if (cls == kClassPerson) {
      ++c.person;
      c.person_moving += MaskMoving(*it);
    } else if (cls == kClassMovable) {
      ++c.movable;
      c.movable_moving += MaskMoving(*it);
    } else {
      EXPECT_FALSE(MaskMoving(*it)) << "the static world never moves";
    }
  }
  return c;
}

TEST(SceneMasks, StaticPresetHasNoDynamicPixels) {
  const SynthSequence s(Options(Preset::kStatic, 400));
  EXPECT_TRUE(s.scene().actors.empty());
  for (int i = 0; i < s.size(); i += 130) EXPECT_EQ(cv::countNonZero(s.Render(i).mask), 0) << i;
}

// A person's head centre, projected with the ground-truth pose, is labelled
// person and lies just behind the visible surface there.
TEST(SceneMasks, MaskCoversThePeople) {
  const SynthSequence s(Options(Preset::kWalkingStatic, 900));
  const CameraIntrinsics& camera = s.options().camera;
  int in_view = 0, unoccluded = 0;
  for (int i = 0; i < s.size(); i += 60) {
    const RenderedFrame f = s.Render(i);
    for (const Actor& actor : s.scene().actors) {
      const SE3d head = actor.pose_at(f.scene_time)[kHead];
      const Eigen::Vector3d centre_cam = f.world_from_cam.Inverse() * (head * Eigen::Vector3d(0, 0, -0.03));
      const Eigen::Vector2d uv = camera.Project(centre_cam);
      const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
      if (u < 0 || v < 0 || u >= camera.width || v >= camera.height) continue;
      ++in_view;
      // Only the other walker can pass in front of a head (nothing else is that high).
      EXPECT_EQ(MaskClass(f.mask.at<std::uint8_t>(v, u)), kClassPerson) << "frame " << i;
      const float z = f.true_depth.at<float>(v, u);
      if (z < centre_cam.z() - 0.2) continue;
      EXPECT_GT(z, centre_cam.z() - 0.12) << "frame " << i;
      EXPECT_LT(z, centre_cam.z()) << "frame " << i;
      ++unoccluded;
    }
  }
  EXPECT_GE(in_view, 12);
  EXPECT_GE(unoccluded, in_view * 2 / 3);
}

// A walker's pixels are flagged moving while it walks and not while it
// stands (rendered alone, so the other walker's state does not interfere).
TEST(SceneMasks, WalkersAreFlaggedMovingOnlyWhileTheyMove) {
  const SynthSequence s(Options(Preset::kWalkingXyz, 900));
  Scene first_only = s.scene();
  first_only.actors.resize(1);
  int cruising = 0, standing = 0;
  for (int i = 0; i < s.size() && (cruising < 3 || standing < 3); i += 10) {
    const double t = s.camera_path()[static_cast<std::size_t>(i)].timestamp - s.camera_path()[0].timestamp;
    const Actor& walker = s.scene().actors[0];
    const double torso_motion = (walker.pose_at(t)[kTorso].translation() -
                                 walker.pose_at(t - 1.0 / 30.0)[kTorso].translation()).norm();
    const bool walking = torso_motion > 0.02, still = ActorMotion(walker, t) < 1e-3;
    if (!(walking && cruising < 3) && !(still && standing < 3)) continue;
    std::mt19937 rng(1);
    const RenderedFrame f = RenderFrame(first_only, s.options().camera,
                                        {s.camera_path()[static_cast<std::size_t>(i)].world_from_cam(), t},
                                        s.options().render, rng);
    const MaskCounts c = Count(f.mask);
    if (c.person < 2000) continue;  // mostly out of view
    if (walking) {
      EXPECT_GT(c.person_moving, 0.8 * c.person) << "frame " << i;
      ++cruising;
    } else {
      EXPECT_EQ(c.person_moving, 0) << "frame " << i;
      ++standing;
    }
  }
  EXPECT_EQ(cruising, 3);
  EXPECT_EQ(standing, 3);
}

// As in TUM fr3/walking_*, the people walk close to the camera and cover a
// large part of the image for long stretches (ORB-SLAM's failure there).
TEST(SceneMasks, WalkersCoverMuchOfTheImage) {
  RenderOptions render;  // masks only: no sensor noise
  render.depth.enabled = false;
  render.colour_noise_sigma = 0;
  render.lens_blur_sigma_px = 0;
  const CameraIntrinsics camera = CameraPreset("freiburg3");
  int frames = 0, large = 0;
  double sum = 0;
  for (const std::uint32_t seed : {1u, 4u}) {
    const Scene scene = BuildScene(Preset::kWalkingStatic, seed);  // all walking presets share it
    for (const Preset preset : {Preset::kWalkingStatic, Preset::kWalkingXyz}) {
      const Trajectory path = PresetCameraPath(preset, seed, scene.viewpoint, 900, 30.0, 0.0);
      for (std::size_t i = 0; i < path.size(); i += 90, ++frames) {
        std::mt19937 rng(1);
        const RenderedFrame f = RenderFrame(scene, camera, {path[i].world_from_cam(), path[i].timestamp}, render, rng);
        cv::Mat dynamic;
        cv::bitwise_and(f.mask, cv::Scalar(127), dynamic);
        const double fraction = cv::countNonZero(dynamic) / static_cast<double>(dynamic.total());
        sum += fraction;
        large += fraction >= 0.15 ? 1 : 0;
      }
    }
  }
  EXPECT_GE(large, frames / 2) << "frames with at least 15 % people";
  EXPECT_GT(sum / frames, 0.15) << "mean fraction of people pixels";
  EXPECT_LT(sum / frames, 0.6) << "the room stays visible";
}

// Sitting people are mostly still (gestures aside); the box slides now and then.
TEST(SceneMasks, SittersMostlyStillTheBoxSometimesMoves) {
  const SynthSequence s(Options(Preset::kSittingStatic, 600));
  long person = 0, person_moving = 0;
  int sampled = 0, box_frames = 0, box_moving_frames = 0, box_still_frames = 0;
  for (int i = 0; i < s.size(); i += 20, ++sampled) {
    const MaskCounts c = Count(s.Render(i).mask);
    person += c.person;
    person_moving += c.person_moving;
    if (c.movable > 500) {
      ++box_frames;
      if (c.movable_moving == c.movable) ++box_moving_frames;
      if (c.movable_moving == 0) ++box_still_frames;
    }
  }
  EXPECT_GT(person, 0);
  EXPECT_GT(person_moving, 0) << "gestures";
  EXPECT_LT(person_moving, 0.2 * person);
  EXPECT_GE(box_frames, sampled * 9 / 10) << "the box on the desk is in view";
  EXPECT_GE(box_moving_frames, 3);
  EXPECT_GE(box_still_frames, 10);
}

TEST(Actors, WalkerWalksAtItsSpeedAndStandsStill) {
  PersonLook look;
  WalkerParams p;
  p.route = {{{-1.5, 1.5}, 3.0}, {{1.5, 1.5}, 3.0}};  // back and forth, standing 3 s at either end
  p.walk.speed = 1.1;
  p.walk.ramp_s = 0.5;
  const Actor walker = MakeWalker(look, p);
  ASSERT_EQ(walker.parts.size(), static_cast<std::size_t>(kPersonPartCount));
  // Cruising from 0.5 s to 2.7 s along +x: the root covers speed * time.
  const Eigen::Vector3d a = walker.pose_at(1.4)[kTorso].translation(), b = walker.pose_at(1.6)[kTorso].translation();
  EXPECT_NEAR((b - a).norm() / 0.2, p.walk.speed, 0.2 * p.walk.speed);
  EXPECT_GT(b.x(), a.x());
  // Arrives at 3 / 1.1 + 0.5 = 3.23 s, turns round (pi at 3 rad/s: 1.05 s), stands until 7.27 s.
  EXPECT_GT(ActorMotion(walker, 3.8), 0.01) << "turning on the spot";
  for (double t = 4.4; t < 6.2; t += 0.25) EXPECT_LT(ActorMotion(walker, t), 1e-9) << t;
  // Standing upright with the feet on the floor and the head at its height, facing back (-x).
  const auto parts = walker.pose_at(5.0);
  EXPECT_NEAR((parts[kFootLeft] * Eigen::Vector3d(0, 0, -0.07)).z(), 0.0, 0.01);
  EXPECT_NEAR((parts[kHead] * Eigen::Vector3d(0, 0, 0.1)).z(), look.height, 0.03);
  EXPECT_NEAR(parts[kTorso].translation().x(), 1.5, 0.05);
  EXPECT_LT((parts[kTorso].so3() * Eigen::Vector3d::UnitX()).x(), -0.99) << "faces the way back";
}

// The walkers (all parts but the feet, which touch the floor) never enter
// the furniture or the walls.
TEST(Scene, WalkersStayInTheFreeSpace) {
  const Scene scene = BuildScene(Preset::kWalkingStatic, 4);
  ASSERT_EQ(scene.actors.size(), 2u);
  for (const Actor& actor : scene.actors) {
    for (double t = 0; t < 60; t += 0.1) {
      const std::vector<SE3d> poses = actor.pose_at(t);
      for (std::size_t k = 0; k < actor.parts.size(); ++k) {
        if (k == kFootLeft || k == kFootRight) continue;
        for (const Eigen::Vector3f& v : actor.parts[k].mesh.positions) {
          ASSERT_TRUE(InFreeSpace(scene, poses[k] * v.cast<double>(), 0.0)) << actor.kind << " part " << k << " t " << t;
        }
      }
    }
  }
}

TEST(Actors, SitterSitsOnTheSeatFacingTheCamera) {
  PersonLook look;
  SitterParams p;
  p.seat = room::kSeatLeft;
  p.heading = -std::numbers::pi / 2;
  const Actor sitter = MakeSitter(look, p);
  const auto parts = sitter.pose_at(0.0);
  const Eigen::Vector3d knee = parts[kLowerLegLeft].translation();
  EXPECT_NEAR(knee.z(), room::kSeatHeight + 0.07, 0.05) << "thighs level with the seat";
  EXPECT_LT(knee.y(), p.seat.y() - 0.35) << "knees point to the camera (-y)";
  EXPECT_LT(knee.z(), room::kDeskMax.z() - 0.1) << "legs fit under the desk";
}

// Smallest distance [m] from the camera centre to any vertex of any actor along `path`.
double ClosestApproach(const Scene& scene, const Trajectory& path) {
  double closest = 1e9;
  for (const StampedPose& pose : path) {
    const double t = pose.timestamp - path.front().timestamp;
    for (const Actor& actor : scene.actors) {
      const std::vector<SE3d> poses = actor.pose_at(t);
      // Nothing of a person is more than 1 m from its torso's origin.
      if ((poses[kTorso].translation() - pose.translation).norm() > 1.0 + closest) continue;
      for (std::size_t k = 0; k < actor.parts.size(); ++k) {
        for (const Eigen::Vector3f& v : actor.parts[k].mesh.positions) {
          closest = std::min(closest, (poses[k] * v.cast<double>() - pose.translation).norm());
        }
      }
    }
  }
  return closest;
}

constexpr double kCameraClearance = 0.25;  // [m] from the camera centre to a person's surface

// The walking presets share their scene (room, people) for a seed; only the camera differs.
TEST(Scene, CameraKeepsClearOfTheWalkers) {
  for (const std::uint32_t seed : {1u, 2u}) {
    const Scene scene = BuildScene(Preset::kWalkingXyz, seed);
    for (const Preset preset : {Preset::kWalkingXyz, Preset::kWalkingRpy, Preset::kWalkingHalfsphere,
                                Preset::kWalkingStatic}) {
      const Trajectory path = PresetCameraPath(preset, seed, scene.viewpoint, 1800, 30.0, 0.0);
      EXPECT_GT(ClosestApproach(scene, path), kCameraClearance) << PresetName(preset) << " seed " << seed;
    }
  }
}

// The real fr3 walking trajectories, replayed at their frame times, never take
// the camera into a walker either.
TEST(Scene, ReplayedTumCamerasKeepClearOfTheWalkers) {
  DLSLAM_REQUIRE_SHARED_DATA(tum, "tum/gt");
  for (const std::uint32_t seed : {1u, 2u}) {
    const Scene scene = BuildScene(Preset::kWalkingXyz, seed);
    for (const std::string name : {"walking_xyz", "walking_static", "walking_rpy", "walking_halfsphere"}) {
      const std::string file = "rgbd_dataset_freiburg3_" + name + ".txt";
      std::vector<double> times;
      for (const io::TextRow& row : io::ReadTextTable(tum.parent_path() / "associations" / file).rows) {
        times.push_back(io::ParseDouble(row.fields[0], file, row.line, "t"));
      }
      const ReplayPath replay = ReplayCameraPath(io::ReadTumTrajectory(tum / file), times, scene.viewpoint);
      EXPECT_GT(ClosestApproach(scene, replay.path), kCameraClearance) << name << " seed " << seed;
    }
  }
}

TEST(Scene, FreeSpace) {
  const Scene scene = BuildScene(Preset::kStatic, 1);
  EXPECT_TRUE(InFreeSpace(scene, room::kViewpoint, 0.2));
  EXPECT_FALSE(InFreeSpace(scene, Eigen::Vector3d(0, 1.7, 0.5), 0.0)) << "under the desk";
  EXPECT_FALSE(InFreeSpace(scene, Eigen::Vector3d(0, 3.5, 1.5), 0.0)) << "behind the far wall";
  EXPECT_FALSE(InFreeSpace(scene, Eigen::Vector3d(0, 3.3, 1.5), 0.2)) << "too close to the wall";
  EXPECT_THROW(ParsePreset("walking_fast"), Error);
}

}  // namespace
}  // namespace dlslam::synth
