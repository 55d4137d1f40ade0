#include "dlslam/data/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "dlslam/util/check.h"

namespace dlslam {
namespace {

TEST(Camera, ProjectUnprojectRoundTrip) {
  const CameraIntrinsics c = CameraPreset("freiburg3");
  const Eigen::Vector3d p(0.3, -0.2, 2.1);
  const Eigen::Vector2d uv = c.Project(p);
  EXPECT_LT((c.Unproject(uv, p.z()) - p).norm(), 1e-12);
}

TEST(Camera, PresetsMatchPublishedTumValues) {
  const CameraIntrinsics fr1 = CameraPreset("fr1");
  EXPECT_EQ(fr1.name, "freiburg1");
  EXPECT_DOUBLE_EQ(fr1.fx, 517.306408);
  EXPECT_DOUBLE_EQ(fr1.k3, 1.163314);
  EXPECT_DOUBLE_EQ(CameraPreset("freiburg2").cy, 249.701764);
  const CameraIntrinsics fr3 = CameraPreset("freiburg3");
  EXPECT_FALSE(fr3.HasDistortion());
  EXPECT_DOUBLE_EQ(fr3.depth_factor, 5000.0);
  EXPECT_NO_THROW(fr3.Check());
}

TEST(Camera, BonnPresetMatchesItsWebPage) {
  // ipb.uni-bonn.de/data/rgbd-dynamic-dataset: fx fy cx cy and d0..d4.
  const CameraIntrinsics bonn = CameraPreset("bonn");
  EXPECT_DOUBLE_EQ(bonn.fx, 542.822841);
  EXPECT_DOUBLE_EQ(bonn.cy, 237.756098);
  EXPECT_DOUBLE_EQ(bonn.k1, 0.039903);
  EXPECT_DOUBLE_EQ(bonn.k2, -0.099343);
  EXPECT_DOUBLE_EQ(bonn.p1, -0.000730);
  EXPECT_DOUBLE_EQ(bonn.p2, -0.000144);
  EXPECT_DOUBLE_EQ(bonn.depth_factor, 5000.0);
}

TEST(Camera, UnknownPresetIsAnError) { EXPECT_THROW(CameraPreset("freiburg9"), Error); }

TEST(Camera, CheckRejectsNonsense) {
  CameraIntrinsics c;
  c.fx = -1;
  EXPECT_THROW(c.Check(), Error);
  c = CameraIntrinsics();
  c.cx = 700;
  EXPECT_THROW(c.Check(), Error);
  c = CameraIntrinsics();
  c.depth_factor = 0;
  EXPECT_THROW(c.Check(), Error);
}

TEST(Camera, CheckAcceptsEveryRealLensAndRefusesAbsurdOnes) {
  for (const char* preset : {"fr1", "fr2", "fr3", "bonn"}) {
    EXPECT_NO_THROW(CameraPreset(preset).Check()) << preset;
  }
  const auto refused = [](auto change) {
    CameraIntrinsics c = CameraPreset("bonn");
    change(c);
    try {
      c.Check();
    } catch (const Error& e) {
      // A user-facing sentence, not an internal check with a source path.
      return std::string(e.what()).find("check failed") == std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.k1 = 1e10; }));   // magnifies the corners
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.k1 = -5; }));     // folds back
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.k3 = -1e6; }));
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.p1 = 3; }));
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.k2 = std::nan(""); }));
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.depth_factor = 1e-300; }));
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.depth_factor = 1e300; }));
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.fx = 4294967831.0; }));
  EXPECT_TRUE(refused([](CameraIntrinsics& c) { c.width = 1 << 30; }));
  EXPECT_FALSE(refused([](CameraIntrinsics& c) { c.k1 = -0.3; c.k2 = 0.1; }));  // strong barrel
  EXPECT_FALSE(refused([](CameraIntrinsics& c) { c.depth_factor = 1000; }));
}

TEST(Camera, DistortionOfCentreIsIdentityAndMatchesFormula) {
  const CameraIntrinsics c = CameraPreset("fr1");
  EXPECT_EQ(c.Distort(Eigen::Vector2d::Zero()), Eigen::Vector2d::Zero());
  const double x = 0.2, y = -0.1, r2 = x * x + y * y;
  const double radial = 1 + c.k1 * r2 + c.k2 * r2 * r2 + c.k3 * r2 * r2 * r2;
  const Eigen::Vector2d d = c.Distort({x, y});
  EXPECT_NEAR(d.x(), x * radial + 2 * c.p1 * x * y + c.p2 * (r2 + 2 * x * x), 1e-15);
  EXPECT_NEAR(d.y(), y * radial + c.p1 * (r2 + 2 * y * y) + 2 * c.p2 * x * y, 1e-15);
}

}  // namespace
}  // namespace dlslam
