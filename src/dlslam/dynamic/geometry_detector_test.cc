#include "dlslam/dynamic/geometry_detector.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "dlslam/dynamic/test_scenes.h"
#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

using testing::LookAt;
using testing::TestCamera;

// Reference keyframe at the origin sees a wall at z = 3 m (a grid of
// keypoints, ids 0..) and a box at 1.5 m on the left (ids 1000..). In the
// current frame (camera 5 cm to the right) the box has gone and a person
// stands at 1.2 m on the right, in front of the wall.
struct Scene {
  CameraIntrinsics camera = TestCamera();
  std::vector<ReferenceView> references;
  SE3d current = LookAt({0.05, 0.0, 0.0}, {0.05, 0.0, 3.0});
  cv::Rect person{400, 150, 100, 250};
  cv::Mat depth;

  Scene() {
    ReferenceView view;
    view.cam_from_world = SE3d::Identity();
    std::uint64_t id = 0;
    const cv::Rect box(55, 195, 110, 110);  // the wall behind it was hidden
    for (int v = 20; v < 470; v += 15) {
      for (int u = 20; u < 630; u += 15) {
        if (!box.contains({u, v})) view.points.push_back({camera.Unproject({u, v}, 3.0), id++});
      }
    }
    for (int v = 200; v < 300; v += 15) {
      for (int u = 60; u < 160; u += 15) {
        view.points.push_back({camera.Unproject({u, v}, 1.5), 1000 + id++});
      }
    }
    references.push_back(view);
    // Current depth: the wall is a plane z = 3 in the world; the camera only
    // translates along x, so its depth stays 3 m.
    depth = testing::ConstantDepth(camera, 3.0f);
    depth(person).setTo(1.2f);
  }
};

GeometryOptions Options(SearchKind kind) {
  GeometryOptions options;
  options.search = kind;
  return options;
}

TEST(GeometryDetector, FlagsThePersonAndReportsTheVanishedBox) {
  for (const SearchKind kind : {SearchKind::kExhaustive, SearchKind::kAntColony}) {
    const Scene s;
    GeometryDetector detector(Options(kind));
    const GeometryResult r = detector.Detect(s.depth, s.camera, s.current, s.references);
    SCOPED_TRACE(ToString(kind));
    ASSERT_EQ(r.dynamic_mask.size(), s.depth.size());
    EXPECT_EQ(r.points.size(), r.labels.size());
    EXPECT_EQ(r.points_projected, static_cast<int>(r.points.size()));
    // Region growing covers exactly the person's silhouette.
    EXPECT_EQ(cv::countNonZero(r.dynamic_mask), s.person.area());
    EXPECT_EQ(cv::countNonZero(r.dynamic_mask(s.person)), s.person.area());
    EXPECT_GT(r.points_dynamic, 0);
    // Every tested point inside the person is dynamic; none outside.
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      const cv::Point px(static_cast<int>(std::lround(r.points[i].pixel.x())),
                         static_cast<int>(std::lround(r.points[i].pixel.y())));
      const bool inside = s.person.contains(px);
      if (r.labels[i] == PointLabel::kDynamic) {
        EXPECT_TRUE(inside) << px;
      }
    }
    // The box's points (ids >= 1000) have vanished; all found by both
    // strategies (the ant colony expands around vanished points too).
    EXPECT_EQ(r.points_vanished, static_cast<int>(r.vanished_ids.size()));
    EXPECT_EQ(r.vanished_ids.size(), 7u * 7u);
    for (const std::uint64_t id : r.vanished_ids) EXPECT_GE(id, 1000u);
    if (kind == SearchKind::kExhaustive) {
      EXPECT_EQ(r.points_tested, r.points_projected);
    } else {
      EXPECT_LT(r.points_tested, r.points_projected / 2);
    }
  }
}

TEST(GeometryDetector, UsesOnlyTheFirstReferenceViews) {
  Scene s;
  // A second view whose points lie 1.5 times farther (the wall's behind the
  // current wall: dynamic); with max_reference_views = 1 it is ignored.
  ReferenceView behind = s.references[0];
  for (ReferencePoint& p : behind.points) p.position_world *= 1.5;
  s.references.push_back(behind);
  GeometryOptions options = Options(SearchKind::kExhaustive);
  options.multiview.max_reference_views = 1;
  GeometryDetector detector(options);
  const GeometryResult one = detector.Detect(s.depth, s.camera, s.current, s.references);
  for (const ProjectedPoint& p : one.points) EXPECT_EQ(p.view, 0);
  options.multiview.max_reference_views = 2;
  GeometryDetector both(options);
  const GeometryResult two = both.Detect(s.depth, s.camera, s.current, s.references);
  EXPECT_GT(two.points_projected, one.points_projected);
  EXPECT_GT(two.points_dynamic, one.points_dynamic);
}

TEST(GeometryDetector, NoReferencesNoDetections) {
  const Scene s;
  GeometryDetector detector(GeometryOptions{});
  const GeometryResult r = detector.Detect(s.depth, s.camera, s.current, {});
  EXPECT_EQ(r.points_projected, 0);
  EXPECT_EQ(cv::countNonZero(r.dynamic_mask), 0);
}

TEST(GeometryDetector, WhatMovedInGrowsOverTheMoverAndIsRemoved) {
  // The dense check found only the person's leading strip (the rest stands
  // where they stood before): with no reference point on or behind them,
  // the strip seeds the fill, which covers the person and stops at the wall.
  const Scene s;
  GeometryDetector detector(GeometryOptions{});
  cv::Mat moved_in = cv::Mat::zeros(s.depth.size(), CV_8UC1);
  const cv::Rect strip(s.person.x, s.person.y, 20, s.person.height);
  moved_in(strip).setTo(255);
  const GeometryResult r = detector.Detect(s.depth, s.camera, s.current, {}, moved_in);
  EXPECT_EQ(r.points_projected, 0);
  EXPECT_GT(cv::countNonZero(r.dynamic_mask(s.person)), 0.95 * s.person.area());
  cv::Mat outside = r.dynamic_mask.clone();
  outside(s.person).setTo(0);
  EXPECT_EQ(cv::countNonZero(outside), 0);
  // Without it, nothing.
  EXPECT_EQ(cv::countNonZero(detector.Detect(s.depth, s.camera, s.current, {}).dynamic_mask), 0);
  EXPECT_THROW(detector.Detect(s.depth, s.camera, s.current, {}, cv::Mat(10, 10, CV_8UC1)), Error);
}

// A still box before a wall, seen from the reference camera and from 0.3 m to
// its left: the wall points the reference saw past the box's edge are hidden
// by parallax, not by motion. With the parallax check nothing is flagged;
// without it a region grows over the box.
TEST(GeometryDetector, ParallaxBehindAStillBoxFlagsNothing) {
  const CameraIntrinsics camera = TestCamera();
  const SE3d current = LookAt({-0.3, 0.0, 0.0}, {-0.3, 0.0, 3.0});
  // The reference keyframe's keypoints: every 10th pixel, at its depth.
  const cv::Mat reference_depth = testing::BoxBeforeWallDepth(camera, Eigen::Vector3d::Zero());
  ReferenceView view{SE3d::Identity(), {}};
  for (int v = 5; v < camera.height; v += 10) {
    for (int u = 5; u < camera.width; u += 10) {
      view.points.push_back({camera.Unproject({u, v}, reference_depth.at<float>(v, u)), view.points.size()});
    }
  }
  const cv::Mat depth = testing::BoxBeforeWallDepth(camera, current.Inverse().translation());
  GeometryOptions options;
  options.search = SearchKind::kExhaustive;
  options.multiview.parallax_occlusion_check = false;
  GeometryDetector without(options);
  const GeometryResult old = without.Detect(depth, camera, current, {view});
  EXPECT_GT(old.points_dynamic, 40);
  EXPECT_GT(cv::countNonZero(old.dynamic_mask), 0);
  // With the check, clearance 0: every one of them is parallax.
  options.multiview.parallax_occlusion_check = true;
  options.multiview.parallax_clearance_px = 0;
  GeometryDetector exact(options);
  const GeometryResult r = exact.Detect(depth, camera, current, {view});
  EXPECT_EQ(r.points_dynamic, 0);
  EXPECT_EQ(std::count(r.labels.begin(), r.labels.end(), PointLabel::kOccluded), old.points_dynamic);
  EXPECT_EQ(cv::countNonZero(r.dynamic_mask), 0);
  // With the default clearance only the points whose reference ray grazed
  // the box's edge (one column of the 10 px grid) stay moving.
  options.multiview.parallax_clearance_px = MultiViewOptions{}.parallax_clearance_px;
  GeometryDetector cleared(options);
  const GeometryResult c = cleared.Detect(depth, camera, current, {view});
  EXPECT_LT(c.points_dynamic, old.points_dynamic / 3);
}

TEST(GeometryDetector, RejectsBadDepthAndOptions) {
  const Scene s;
  GeometryDetector detector(GeometryOptions{});
  EXPECT_THROW(detector.Detect(cv::Mat(480, 640, CV_16UC1), s.camera, s.current, s.references),
               Error);
  EXPECT_THROW(detector.Detect(cv::Mat(240, 320, CV_32FC1), s.camera, s.current, s.references),
               Error);
  GeometryOptions bad;
  bad.ant.rho = 2;
  EXPECT_THROW(GeometryDetector{bad}, Error);
  bad = {};
  bad.region.max_region_pixels = 0;
  EXPECT_THROW(bad.Check(), Error);
}

TEST(SearchKind, NamesRoundTrip) {
  EXPECT_EQ(ParseSearchKind("exhaustive"), SearchKind::kExhaustive);
  EXPECT_EQ(ParseSearchKind("ant"), SearchKind::kAntColony);
  EXPECT_EQ(ParseSearchKind(ToString(SearchKind::kAntColony)), SearchKind::kAntColony);
  EXPECT_EQ(ToString(SearchKind::kExhaustive), "exhaustive");
  EXPECT_THROW(ParseSearchKind("greedy"), Error);
}

}  // namespace
}  // namespace dlslam::dynamic
