#pragma once
// Helpers shared by tracker_test.cc and tracker_occlusion_test.cc.

#include <gtest/gtest.h>

#include <memory>

#include "dlslam/tracking/tracker.h"
#include "tests/support/landmark_scene.h"

namespace dlslam::tracker_testing {

// Distance between the camera centres of two cam_from_world poses [m].
inline double CentreDistance(const SE3d& a, const SE3d& b) {
  return (a.Inverse().translation() - b.Inverse().translation()).norm();
}

// A frame without keypoints at `timestamp`: the lens covered, a black image.
inline std::shared_ptr<Frame> CoveredFrame(const testing::LandmarkScene& scene, double timestamp) {
  return std::make_shared<Frame>(
      Frame::Create(timestamp, {}, cv::Mat(0, 32, CV_8UC1), cv::Mat(), scene.camera, scene.pyramid));
}

// Tracks frames 0..frames-1 of the path in `scene`; fails on the first that is not kOk.
inline ::testing::AssertionResult TracksThePath(Tracker& tracker, const testing::LandmarkScene& scene, int frames) {
  for (int i = 0; i < frames; ++i) {
    const TrackingState state = tracker.Track(scene.MakeFrame(testing::SmoothRoomPath(i), i / 30.0, i)).state;
    if (state != TrackingState::kOk) {
      return ::testing::AssertionFailure() << "frame " << i << ": " << ToString(state);
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace dlslam::tracker_testing
