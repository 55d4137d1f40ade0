#include "dlslam/synth/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dlslam/synth/renderer.h"
#include "dlslam/synth/room.h"
#include "dlslam/synth/sequence.h"
#include "dlslam/util/check.h"

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

// Walkers share one walk/stop schedule: while they cruise almost every person
// pixel is flagged moving, while they stand none is.
TEST(SceneMasks, WalkersAreFlaggedMovingOnlyWhileTheyMove) {
  const SynthSequence s(Options(Preset::kWalkingXyz, 900));
  int cruising = 0, standing = 0;
  for (int i = 0; i < s.size() && (cruising < 3 || standing < 3); i += 10) {
    const double t = s.camera_path()[static_cast<std::size_t>(i)].timestamp - s.camera_path()[0].timestamp;
    const double motion = ActorMotion(s.scene().actors[0], t);
    const bool walking = motion > 0.02, still = motion < 1e-3;
    if (!(walking && cruising < 3) && !(still && standing < 3)) continue;
    const MaskCounts c = Count(s.Render(i).mask);
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
  p.walk_s = 2.0;
  p.stop_s = 3.0;
  p.ramp_s = 0.5;
  p.speed = 1.1;
  const Actor walker = MakeWalker(look, p);
  ASSERT_EQ(walker.parts.size(), static_cast<std::size_t>(kPersonPartCount));
  // Cruising from 0.5 s to 2.5 s: the root covers speed * time along the loop.
  const double chord = (walker.pose_at(1.6)[kTorso].translation() - walker.pose_at(1.4)[kTorso].translation()).norm();
  EXPECT_NEAR(chord / 0.2, p.speed, 0.2 * p.speed);
  for (double t = 3.05; t < 6.0; t += 0.25) EXPECT_LT(ActorMotion(walker, t), 1e-9) << t;  // standing
  // Standing upright with the feet on the floor and the head at its height.
  const auto parts = walker.pose_at(4.0);
  EXPECT_NEAR((parts[kFootLeft] * Eigen::Vector3d(0, 0, -0.07)).z(), 0.0, 0.01);
  EXPECT_NEAR((parts[kHead] * Eigen::Vector3d(0, 0, 0.1)).z(), look.height, 0.03);
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
