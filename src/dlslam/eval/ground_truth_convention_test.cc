#include "dlslam/eval/ground_truth_convention.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

TEST(GroundTruthConvention, NamesRoundTripAndUnknownNamesListTheChoices) {
  for (const GroundTruthConvention c : {GroundTruthConvention::kAsPublished, GroundTruthConvention::kBonnCamera}) {
    EXPECT_EQ(ParseGroundTruthConvention(ToString(c)), c);
  }
  try {
    ParseGroundTruthConvention("camera");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("published | bonn-camera"), std::string::npos) << e.what();
  }
}

TEST(GroundTruthConvention, BonnMarkerPoseBecomesTheCamerasAsTheDatasetsToolComputesIt) {
  // The first pose of rgbd_bonn_crowd frames 280-579 as published, and the
  // camera pose the dataset's formula gives (T_ros * T * T_ros * T_m, T_m's
  // rotation by SVD), computed independently with numpy (from the 6-digit
  // quaternion unnormalised, hence the tolerances).
  const SE3d marker(Eigen::Quaterniond(-0.982792, 0.171586, 0.0638464, 0.024538),
                    Eigen::Vector3d(-0.416097, -1.55391, 1.50676));
  const SE3d camera = BonnCameraFromMarker(marker);
  EXPECT_NEAR((camera.translation() - Eigen::Vector3d(0.425365360355, 1.492394821456, -1.546515464507)).norm(), 0,
              1e-8);
  const Eigen::Quaterniond expected(0.142190469138, 0.982199728830, 0.001115018993, -0.122739012868);
  EXPECT_NEAR(camera.unit_quaternion().angularDistance(expected), 0, 1e-6);
}

TEST(GroundTruthConvention, CameraMotionTurnsAsTheMarkersAndPublishedPosesStay) {
  // Marker and camera are one rigid body: every relative motion turns by the
  // same angle, and moves by at most the lever arm (1.9 cm) times the turn more.
  const SE3d a(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
               Eigen::Vector3d(0.5, -1.0, 1.5));
  const SE3d b = a * SE3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(-1, 0, 2).normalized())),
                          Eigen::Vector3d(0.1, 0.05, -0.02));
  const SE3d marker_motion = a.Inverse() * b;
  const SE3d camera_motion = BonnCameraFromMarker(a).Inverse() * BonnCameraFromMarker(b);
  EXPECT_NEAR(camera_motion.so3().Log().norm(), marker_motion.so3().Log().norm(), 1e-12);
  const double lever_arm = Eigen::Vector3d(0.0113, -0.0098, 0.0111).norm();
  EXPECT_LE(std::abs(camera_motion.translation().norm() - marker_motion.translation().norm()),
            2 * lever_arm * std::sin(0.2 / 2) + 1e-12);
  // A rotation, to machine precision.
  const Eigen::Matrix3d r = BonnCameraFromMarker(a).rotationMatrix();
  EXPECT_NEAR((r * r.transpose() - Eigen::Matrix3d::Identity()).norm(), 0, 1e-12);
  EXPECT_NEAR(r.determinant(), 1, 1e-12);

  const Trajectory published = {StampedPose(1.0, a), StampedPose(2.0, b)};
  const Trajectory same = ToCameraPoses(published, GroundTruthConvention::kAsPublished);
  ASSERT_EQ(same.size(), 2u);
  EXPECT_EQ(same[1].translation, published[1].translation);
  const Trajectory cameras = ToCameraPoses(published, GroundTruthConvention::kBonnCamera);
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[1].timestamp, 2.0);
  EXPECT_NEAR((cameras[1].translation - BonnCameraFromMarker(b).translation()).norm(), 0, 1e-15);
}

}  // namespace
}  // namespace dlslam::eval
