#include "dlslam/synth/composite.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "dlslam/synth/renderer.h"
#include "dlslam/util/check.h"

namespace dlslam::synth {
namespace {

CameraIntrinsics Camera() {
  CameraIntrinsics c;
  c.fx = c.fy = 525;
  c.cx = 319.5;
  c.cy = 239.5;
  return c;
}

// A "photo": a 100x300 person shape (a filled ellipse) on a border.
Cutout Person() {
  Cutout c;
  c.name = "ellipse";
  c.bgr = cv::Mat(340, 140, CV_8UC3, cv::Scalar(30, 60, 200));
  c.mask = cv::Mat::zeros(340, 140, CV_8UC1);
  cv::ellipse(c.mask, cv::Point(70, 170), cv::Size(50, 150), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  return c;
}

// One camera pose at t = 0 (the walkers' lines are laid out in front of it).
Trajectory Path() { return {StampedPose(0.0, SE3d::Identity())}; }

struct Background {
  cv::Mat colour = cv::Mat(480, 640, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::Mat depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(4.0f));  // a wall 4 m away
};

CompositeOptions OnePersonAt(double distance) {
  CompositeOptions o;
  o.people = 1;
  o.min_distance_m = o.max_distance_m = distance;
  o.speed_mps = 0;         // stands still ...
  o.path_length_m = 1e-3;  // ... in the middle of the view
  o.noise_per_m2 = 0;
  return o;
}

TEST(PeopleCompositor, APersonStandsInFrontOfTheWallWithABodyLikeDepth) {
  const Background bg;
  const PeopleCompositor people(Camera(), {Person()}, OnePersonAt(2.0), Path());
  const CompositedFrame f = people.Composite(0.0, SE3d::Identity(), bg.colour, bg.depth);
  const int on = cv::countNonZero(f.mask);
  ASSERT_GT(on, 1000);
  EXPECT_NEAR(f.person_share, on / (640.0 * 480.0), 1e-12);
  EXPECT_EQ(f.mask.at<uchar>(cv::Point(320, 300)) != 0 || f.mask.at<uchar>(cv::Point(320, 250)) != 0, true);
  double z_min = 10, z_max = 0;
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 640; ++u) {
      if (f.mask.at<uchar>(v, u) == 0) {
        EXPECT_EQ(f.depth.at<float>(v, u), 4.0f);  // the background is untouched
        continue;
      }
      EXPECT_EQ(f.mask.at<uchar>(v, u), MaskValue(kClassPerson, true));
      const float z = f.depth.at<float>(v, u);
      if (z == 0) continue;  // the outline's band without depth
      z_min = std::min<double>(z_min, z);
      z_max = std::max<double>(z_max, z);
      EXPECT_EQ(f.colour.at<cv::Vec3b>(v, u), cv::Vec3b(30, 60, 200));
    }
  }
  // In front of the wall, at about 2 m; the torso nearer than the edges by
  // up to half the body depth.
  EXPECT_GT(z_min, 2.0 - 0.125 - 1e-3);
  EXPECT_LT(z_max, 2.0 + 1e-3);
  EXPECT_GT(z_max - z_min, 0.06);
}

TEST(PeopleCompositor, ANearerRealSurfaceHidesThePerson) {
  Background bg;
  bg.depth(cv::Rect(0, 0, 320, 480)).setTo(1.0f);  // a cupboard at 1 m on the left half
  const PeopleCompositor people(Camera(), {Person()}, OnePersonAt(2.0), Path());
  const CompositedFrame f = people.Composite(0.0, SE3d::Identity(), bg.colour, bg.depth);
  EXPECT_EQ(cv::countNonZero(f.mask(cv::Rect(0, 0, 320, 480))), 0);
  EXPECT_GT(cv::countNonZero(f.mask(cv::Rect(320, 0, 320, 480))), 500);
}

TEST(PeopleCompositor, PeopleWalkAndStayInTheWorldWhenTheCameraMoves) {
  const Background bg;
  CompositeOptions o = OnePersonAt(2.0);
  o.speed_mps = 1.0;
  o.path_length_m = 1.0;  // seed 1 starts it away from a turn
  const PeopleCompositor people(Camera(), {Person()}, o, Path());
  const auto centroid = [](const cv::Mat& mask) {
    const cv::Moments m = cv::moments(mask, true);
    return m.m00 > 0 ? m.m10 / m.m00 : -1.0;
  };
  const double x0 = centroid(people.Composite(0.0, SE3d::Identity(), bg.colour, bg.depth).mask);
  const double x1 = centroid(people.Composite(0.04, SE3d::Identity(), bg.colour, bg.depth).mask);
  // 4 cm at about 2 m, up to 35 deg off the image plane: 5-12 px.
  EXPECT_GT(std::abs(x1 - x0), 0.5 * 0.04 * 525 / 2.0);
  EXPECT_LT(std::abs(x1 - x0), 1.2 * 0.04 * 525 / 2.0);
  // The camera steps 0.1 m to the right: a standing person moves left in the image.
  o = OnePersonAt(2.0);
  const PeopleCompositor still(Camera(), {Person()}, o, Path());
  const SE3d moved(SO3d(), Eigen::Vector3d(0.1, 0, 0));
  const double a = centroid(still.Composite(0.0, SE3d::Identity(), bg.colour, bg.depth).mask);
  const double b = centroid(still.Composite(0.0, moved, bg.colour, bg.depth).mask);
  EXPECT_NEAR(a - b, 0.1 * 525 / 2.0, 6.0);
}

TEST(PeopleCompositor, RefusesBadInput) {
  Cutout empty = Person();
  empty.mask.setTo(0);
  EXPECT_THROW(PeopleCompositor(Camera(), {}, CompositeOptions(), Path()), Error);
  EXPECT_THROW(PeopleCompositor(Camera(), {empty}, CompositeOptions(), Path()), Error);
  CompositeOptions bad;
  bad.min_distance_m = 3;
  bad.max_distance_m = 2;
  EXPECT_THROW(PeopleCompositor(Camera(), {Person()}, bad, Path()), Error);
  const PeopleCompositor people(Camera(), {Person()}, CompositeOptions(), Path());
  EXPECT_THROW(people.Composite(0, SE3d::Identity(), cv::Mat(10, 10, CV_8UC3), cv::Mat(10, 10, CV_32FC1)), Error);
}

}  // namespace
}  // namespace dlslam::synth
