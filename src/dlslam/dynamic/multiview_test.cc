#include "dlslam/dynamic/multiview.h"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <cmath>

#include "dlslam/dynamic/test_scenes.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

using testing::ConstantDepth;
using testing::LookAt;
using testing::TestCamera;

// One reference point 2 m in front of a reference camera at the origin; the
// current camera 0.1 m to its right, looking at the point as well.
struct TwoViews {
  CameraIntrinsics camera = TestCamera();
  Eigen::Vector3d point{0.0, 0.0, 2.0};
  std::vector<ReferenceView> references;
  SE3d current = LookAt({0.1, 0.0, 0.0}, {0.0, 0.0, 2.0});
  TwoViews() {
    ReferenceView view;
    view.cam_from_world = SE3d::Identity();
    view.points.push_back({point, 7});
    references.push_back(view);
  }
  ProjectedPoint Projected() const {
    const auto projected = ProjectReferencePoints(references, current, camera);
    EXPECT_EQ(projected.size(), 1u);
    return projected.at(0);
  }
};

TEST(ProjectReferencePoints, PixelDepthAndViewAngle) {
  const TwoViews views;
  const ProjectedPoint p = views.Projected();
  // The current camera looks straight at the point: principal point, depth =
  // distance from (0.1, 0, 0) to (0, 0, 2).
  EXPECT_NEAR(p.pixel.x(), views.camera.cx, 1e-3);
  EXPECT_NEAR(p.pixel.y(), views.camera.cy, 1e-3);
  EXPECT_NEAR(p.projected_depth, std::sqrt(0.01 + 4.0), 1e-5);
  EXPECT_NEAR(p.view_angle_deg, std::atan2(0.1, 2.0) * 180.0 / M_PI, 1e-3);
  EXPECT_EQ(p.view, 0);
  EXPECT_EQ(p.point, 0);
}

TEST(ProjectReferencePoints, DropsPointsBehindOrOutside) {
  TwoViews views;
  views.references[0].points.push_back({Eigen::Vector3d(0, 0, -2), 1});   // behind
  views.references[0].points.push_back({Eigen::Vector3d(5, 0, 2), 2});    // far right
  views.references[0].points.push_back({Eigen::Vector3d(0, -4, 2), 3});   // far above
  const auto projected = ProjectReferencePoints(views.references, views.current, views.camera);
  ASSERT_EQ(projected.size(), 1u);
  EXPECT_EQ(projected[0].point, 0);
}

TEST(ProjectReferencePoints, MaxViewsAndIndices) {
  TwoViews views;
  views.references.push_back(views.references[0]);
  views.references.push_back(views.references[0]);
  std::vector<ProjectedPoint> out(5);
  ProjectReferencePoints(views.references, views.current, views.camera, out, 2);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].view, 1);
}

TEST(ProjectReferencePoints, DistortionMatchesOpenCv) {
  CameraIntrinsics camera = TestCamera();
  camera.k1 = 0.2;
  camera.k2 = -0.3;
  camera.p1 = 0.001;
  camera.p2 = -0.002;
  camera.k3 = 0.05;
  ReferenceView view;
  std::vector<cv::Point3d> cv_points;
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector3d p(-0.8 + 0.4 * i, 0.5 - 0.2 * i, 2.0 + 0.1 * i);
    view.points.push_back({p, static_cast<std::uint64_t>(i)});
    cv_points.emplace_back(p.x(), p.y(), p.z());
  }
  const auto projected = ProjectReferencePoints({view}, SE3d::Identity(), camera);
  ASSERT_EQ(projected.size(), 5u);
  const cv::Matx33d k(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  const std::vector<double> distortion{camera.k1, camera.k2, camera.p1, camera.p2, camera.k3};
  std::vector<cv::Point2d> expected;
  cv::projectPoints(cv_points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, distortion, expected);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(projected[i].pixel.x(), expected[i].x, 1e-2) << i;
    EXPECT_NEAR(projected[i].pixel.y(), expected[i].y, 1e-2) << i;
  }
}

TEST(ClassifyPoint, OccluderInFrontIsDynamic) {
  const TwoViews views;
  const MultiViewOptions options;
  EXPECT_EQ(ClassifyPoint(views.Projected(), ConstantDepth(views.camera, 1.2f), options),
            PointLabel::kDynamic);
}

TEST(ClassifyPoint, MovedPointHasVanished) {
  const TwoViews views;
  EXPECT_EQ(ClassifyPoint(views.Projected(), ConstantDepth(views.camera, 3.0f), {}),
            PointLabel::kVanished);
}

TEST(ClassifyPoint, SameDepthIsStatic) {
  const TwoViews views;
  const ProjectedPoint p = views.Projected();
  EXPECT_EQ(ClassifyPoint(p, ConstantDepth(views.camera, p.projected_depth + 0.02f), {}),
            PointLabel::kStatic);
  EXPECT_EQ(ClassifyPoint(p, ConstantDepth(views.camera, p.projected_depth - 0.02f), {}),
            PointLabel::kStatic);
}

TEST(ClassifyPoint, LargeViewAngleIsUnreliable) {
  TwoViews views;
  // 1.5 m sideways at 2 m: the rays are atan(1.5 / 2) = 37 deg apart.
  views.current = LookAt({1.5, 0.0, 0.0}, views.point);
  const ProjectedPoint p = views.Projected();
  EXPECT_NEAR(p.view_angle_deg, 36.87, 0.01);
  EXPECT_EQ(ClassifyPoint(p, ConstantDepth(views.camera, 1.0f), {}), PointLabel::kUnreliable);
  MultiViewOptions wide;
  wide.max_view_angle_deg = 40;
  EXPECT_EQ(ClassifyPoint(p, ConstantDepth(views.camera, 1.0f), wide), PointLabel::kDynamic);
}

TEST(ClassifyPoint, HoleIsUnknownNearbyDepthIsUsed) {
  const TwoViews views;
  const ProjectedPoint p = views.Projected();
  const int u = static_cast<int>(std::lround(p.pixel.x()));
  const int v = static_cast<int>(std::lround(p.pixel.y()));
  cv::Mat depth = ConstantDepth(views.camera, 1.0f);
  depth(cv::Rect(u - 2, v - 2, 5, 5)).setTo(0.0f);
  EXPECT_EQ(ClassifyPoint(p, depth, {}), PointLabel::kUnknown);
  depth.at<float>(v + 2, u - 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(ClassifyPoint(p, depth, {}), PointLabel::kUnknown);
  depth.at<float>(v + 2, u + 2) = 2.0f;  // a patch corner: static there
  cv::Point where;
  EXPECT_EQ(ClassifyPoint(p, depth, {}, &where), PointLabel::kStatic);
  EXPECT_EQ(where, cv::Point(u + 2, v + 2));
  // Out of the depth range: not a measurement.
  depth.at<float>(v + 2, u + 2) = 9.0f;
  EXPECT_EQ(ClassifyPoint(p, depth, {}), PointLabel::kUnknown);
}

TEST(ClassifyPoint, ItsOwnSurfaceNextToADepthEdgeIsStatic) {
  // The point projects onto the near side of a depth edge (a chair's rim
  // 1 m in front of the wall it lies on); its own wall is 3 px to the right.
  const TwoViews views;
  const ProjectedPoint p = views.Projected();
  const int u = static_cast<int>(std::lround(p.pixel.x()));
  cv::Mat depth = ConstantDepth(views.camera, static_cast<float>(p.projected_depth) - 1.0f);
  depth.colRange(u + 3, depth.cols).setTo(static_cast<float>(p.projected_depth));
  MultiViewOptions off;
  off.agreement_radius_px = 0;
  EXPECT_EQ(ClassifyPoint(p, depth, off), PointLabel::kDynamic);
  MultiViewOptions on;
  on.agreement_radius_px = 3;
  cv::Point where;
  EXPECT_EQ(ClassifyPoint(p, depth, on, &where), PointLabel::kStatic);
  EXPECT_EQ(where.x, u + 3);
  // Beyond the radius the occluder wins: a person standing in front.
  on.agreement_radius_px = 2;
  EXPECT_EQ(ClassifyPoint(p, depth, on), PointLabel::kDynamic);
  // The same for a point whose surface has gone (far side of the edge).
  depth.colRange(0, u + 3).setTo(static_cast<float>(p.projected_depth) + 1.0f);
  EXPECT_EQ(ClassifyPoint(p, depth, off), PointLabel::kVanished);
  on.agreement_radius_px = 3;
  EXPECT_EQ(ClassifyPoint(p, depth, on), PointLabel::kStatic);
}

// The reference camera at the origin, the current one 0.3 m to its left,
// both looking along z, at testing::BoxBeforeWallDepth's still box.
TEST(OcclusionProvesMotion, ParallaxBehindAStillBoxIsNotMotion) {
  const CameraIntrinsics camera = TestCamera();
  const SE3d reference = SE3d::Identity();
  const SE3d current = LookAt({-0.3, 0.0, 0.0}, {-0.3, 0.0, 3.0});
  const cv::Mat depth = testing::BoxBeforeWallDepth(camera, current.Inverse().translation());
  const MultiViewOptions options;
  // A wall point the reference saw just past the box's right edge (its ray
  // crosses z = 1.5 at x = 0.325); from the left the box now hides it.
  const Eigen::Vector3d wall_point(0.65, 0.0, 3.0);
  ReferenceView view{reference, {{wall_point, 1}}};
  const std::vector<ProjectedPoint> projected = ProjectReferencePoints({view}, current, camera);
  ASSERT_EQ(projected.size(), 1u);
  ASSERT_EQ(ClassifyPoint(projected[0], depth, options), PointLabel::kDynamic);  // the depth test alone
  EXPECT_FALSE(OcclusionProvesMotion(wall_point, reference, current, 1.5, depth, camera, options));
  // A point the reference could only have seen had the box not been there
  // (its ray crosses the box's place): the box moved in.
  const Eigen::Vector3d hidden_point(0.45, 0.0, 3.0);
  EXPECT_TRUE(OcclusionProvesMotion(hidden_point, reference, current, 1.5, depth, camera, options));
  // Switched off, every occlusion counts.
  MultiViewOptions off;
  off.parallax_occlusion_check = false;
  EXPECT_TRUE(OcclusionProvesMotion(wall_point, reference, current, 1.5, depth, camera, off));
  // No baseline: the ray is the current one, which meets the surface.
  EXPECT_TRUE(OcclusionProvesMotion(Eigen::Vector3d(0.5, 0.0, 3.0), current, current, 1.5, depth, camera, options));
  // Nothing readable along the ray (a hole): not explained, kept as motion.
  const cv::Mat holes = cv::Mat::zeros(depth.size(), CV_32FC1);
  EXPECT_TRUE(OcclusionProvesMotion(wall_point, reference, current, 1.5, holes, camera, options));
}

TEST(NearestValidDepth, PrefersTheNearestPixel) {
  cv::Mat depth(20, 20, CV_32FC1, cv::Scalar(0.0f));
  depth.at<float>(10 + 2, 10 + 2) = 3.0f;  // distance sqrt(8)
  depth.at<float>(10 + 2, 10 + 0) = 2.0f;  // distance 2
  depth.at<float>(10 - 1, 10 + 1) = 1.5f;  // distance sqrt(2): nearest
  cv::Point where;
  EXPECT_FLOAT_EQ(NearestValidDepth(depth, {10.2f, 9.8f}, 2, 0.1f, 6.0f, &where), 1.5f);
  EXPECT_EQ(where, cv::Point(11, 9));
  EXPECT_FLOAT_EQ(NearestValidDepth(depth, {10.0f, 10.0f}, 1, 0.1f, 6.0f), 1.5f);
  EXPECT_FLOAT_EQ(NearestValidDepth(depth, {10.0f, 10.0f}, 0, 0.1f, 6.0f), 0.0f);
  // At the image border the patch is clipped, not read out of bounds.
  depth.at<float>(0, 0) = 1.0f;
  EXPECT_FLOAT_EQ(NearestValidDepth(depth, {-0.4f, 0.3f}, 2, 0.1f, 6.0f), 1.0f);
  EXPECT_FLOAT_EQ(NearestValidDepth(depth, {19.4f, 19.4f}, 2, 0.1f, 6.0f), 0.0f);
}

TEST(MultiViewOptions, ThresholdGrowsWithDepth) {
  // The same 0.1 m difference: beyond the noise at 1 m, within it at 4 m
  // (Kinect noise grows with z^2).
  const MultiViewOptions options;
  const CameraIntrinsics camera = TestCamera();
  for (const auto& [z, expected] : {std::pair{1.0f, PointLabel::kDynamic},
                                     std::pair{4.0f, PointLabel::kStatic}}) {
    ProjectedPoint p;
    p.pixel = {320, 240};
    p.projected_depth = z;
    EXPECT_EQ(ClassifyPoint(p, ConstantDepth(camera, z - 0.1f), options), expected) << z;
  }
  EXPECT_GT(options.DepthThreshold(4.0), 2 * options.DepthThreshold(1.0));
  EXPECT_DOUBLE_EQ(options.DepthThreshold(0.0), options.depth_threshold_m);
}

TEST(MultiViewOptions, CheckRejectsBadValues) {
  EXPECT_NO_THROW(MultiViewOptions{}.Check());
  auto bad = [](auto mutate) {
    MultiViewOptions o;
    mutate(o);
    return o;
  };
  EXPECT_THROW(bad([](auto& o) { o.max_reference_views = 0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.max_view_angle_deg = 0; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.depth_threshold_m = -0.1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.depth_threshold_per_m2 = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.depth_patch_radius_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.agreement_radius_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.agreement_radius_px = 21; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.parallax_clearance_px = -1; }).Check(), Error);
  EXPECT_THROW(bad([](auto& o) { o.min_depth_m = 7; }).Check(), Error);
  try {
    bad([](auto& o) { o.max_view_angle_deg = 200; }).Check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("200"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dlslam::dynamic
