#include "dlslam/dynamic/mask_fusion.h"

#include <gtest/gtest.h>

#include "dlslam/util/check.h"

namespace dlslam::dynamic {
namespace {

// Two semantic segments (people): A on the left, B on the right; the geometry
// found a moving region C elsewhere; points: 6 static in A, 6 static + 1
// dynamic in B.
struct Scene {
  cv::Rect a{10, 10, 20, 40}, b{60, 10, 20, 40}, c{100, 60, 10, 10};
  cv::Mat semantic = cv::Mat::zeros(100, 120, CV_8UC1);
  GeometryResult geometry;
  Scene() {
    semantic(a).setTo(1);  // any non-zero value marks a segment
    semantic(b).setTo(200);
    geometry.dynamic_mask = cv::Mat::zeros(semantic.size(), CV_8UC1);
    geometry.dynamic_mask(c).setTo(255);
    for (int i = 0; i < 6; ++i) {
      Add(a.x + 2 + 3 * i, a.y + 5 + 5 * i, PointLabel::kStatic);
      Add(b.x + 2 + 3 * i, b.y + 5 + 5 * i, PointLabel::kStatic);
    }
    Add(b.x + 10, b.y + 38, PointLabel::kDynamic);
    Add(a.x + 5, a.y + 1, PointLabel::kUntested);  // no evidence
  }
  void Add(int u, int v, PointLabel label) {
    ProjectedPoint p;
    p.pixel = {static_cast<float>(u), static_cast<float>(v)};
    geometry.points.push_back(p);
    geometry.labels.push_back(label);
  }
};

FusionOptions Policy(FusionPolicy policy) {
  FusionOptions options;
  options.policy = policy;
  options.dilation_px = 0;
  return options;
}

TEST(FuseDynamicMasks, Policies) {
  const Scene s;
  const int area_a = s.a.area(), area_b = s.b.area(), area_c = s.c.area();
  const cv::Mat union_mask = FuseDynamicMasks({s.semantic}, s.geometry, Policy(FusionPolicy::kUnion));
  EXPECT_EQ(cv::countNonZero(union_mask), area_a + area_b + area_c);
  EXPECT_EQ(union_mask.at<std::uint8_t>(s.a.y, s.a.x), 255);
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic}, s.geometry,
                                              Policy(FusionPolicy::kSemanticOnly))),
            area_a + area_b);
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic}, s.geometry,
                                              Policy(FusionPolicy::kGeometryOnly))),
            area_c);
  // A is still (6 static >= 5, no dynamic): kept for SLAM, i.e. not masked;
  // B shows a dynamic point: masked; C: always masked.
  const cv::Mat confirmed =
      FuseDynamicMasks({s.semantic}, s.geometry, Policy(FusionPolicy::kGeometryConfirms));
  EXPECT_EQ(cv::countNonZero(confirmed), area_b + area_c);
  EXPECT_EQ(cv::countNonZero(confirmed(s.a)), 0);
}

TEST(FuseDynamicMasks, GeometryConfirmsNeedsEnoughEvidence) {
  const Scene s;
  FusionOptions options = Policy(FusionPolicy::kGeometryConfirms);
  options.min_static_evidence = 7;  // A has 6: not enough, stays masked
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic}, s.geometry, options)),
            s.a.area() + s.b.area() + s.c.area());
  options.min_static_evidence = 5;
  options.max_dynamic_evidence = 1;  // B's one dynamic point tolerated
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic}, s.geometry, options)), s.c.area());
  // Without a geometry result nothing can be confirmed: the prior stays.
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic}, {}, options)),
            s.a.area() + s.b.area());
}

TEST(FuseDynamicMasks, DilationAndEmptyInputs) {
  const Scene s;
  FusionOptions options = Policy(FusionPolicy::kGeometryOnly);
  options.dilation_px = 2;
  // The 10x10 square dilated by a radius-2 disc: it covers the square grown
  // by 1 px, nothing beyond 2 px, and less than the full 14x14 (round corners).
  const cv::Mat dilated = FuseDynamicMasks({s.semantic}, s.geometry, options);
  const cv::Rect grown1(s.c.x - 1, s.c.y - 1, 12, 12), grown2(s.c.x - 2, s.c.y - 2, 14, 14);
  EXPECT_EQ(cv::countNonZero(dilated(grown1)), 12 * 12);
  EXPECT_EQ(cv::countNonZero(dilated), cv::countNonZero(dilated(grown2)));
  EXPECT_LT(cv::countNonZero(dilated), 14 * 14);
  EXPECT_TRUE(FuseDynamicMasks({}, {}, options).empty());
  const cv::Mat only_semantic = FuseDynamicMasks({s.semantic}, {}, Policy(FusionPolicy::kUnion));
  EXPECT_EQ(cv::countNonZero(only_semantic), s.a.area() + s.b.area());
  const cv::Mat only_geometry = FuseDynamicMasks({}, s.geometry, Policy(FusionPolicy::kSemanticOnly));
  EXPECT_EQ(only_geometry.size(), s.semantic.size());
  EXPECT_EQ(cv::countNonZero(only_geometry), 0);
}

TEST(FuseDynamicMasks, RejectsMismatchedInputs) {
  const Scene s;
  EXPECT_THROW(FuseDynamicMasks({cv::Mat::zeros(10, 10, CV_8UC1)}, s.geometry, {}), Error);
  EXPECT_THROW(FuseDynamicMasks({cv::Mat::zeros(100, 120, CV_32FC1)}, s.geometry, {}), Error);
  FusionOptions bad;
  bad.dilation_px = -1;
  EXPECT_THROW(bad.Check(), Error);
  bad = {};
  bad.min_static_evidence = -1;
  EXPECT_THROW(FuseDynamicMasks({s.semantic}, s.geometry, bad), Error);
  bad = {};
  bad.movable_dynamic_evidence = 0;
  EXPECT_THROW(bad.Check(), Error);
  // A movable-class mask of another size or type.
  EXPECT_THROW(FuseDynamicMasks({s.semantic, cv::Mat::zeros(10, 10, CV_8UC1)}, s.geometry, {}), Error);
  EXPECT_THROW(FuseDynamicMasks({s.semantic, cv::Mat::zeros(100, 120, CV_16UC1)}, s.geometry, {}), Error);
}

// Movable segments (chairs): D with three moving points, E with two, F with
// static points only. Geometry's own region covers only a corner of D.
TEST(FuseDynamicMasks, MovableSegmentsGoWholeWhenGeometrySeesThemMove) {
  Scene s;
  const cv::Rect d{10, 60, 30, 30}, e{50, 60, 30, 30}, f{85, 10, 30, 30};
  cv::Mat movable = cv::Mat::zeros(s.semantic.size(), CV_8UC1);
  for (const cv::Rect& r : {d, e, f}) movable(r).setTo(255);
  for (int i = 0; i < 3; ++i) s.Add(d.x + 3 + 4 * i, d.y + 3, PointLabel::kDynamic);
  s.Add(e.x + 3, e.y + 3, PointLabel::kDynamic);
  s.Add(e.x + 9, e.y + 3, PointLabel::kVanished);
  for (int i = 0; i < 6; ++i) s.Add(f.x + 3 + 4 * i, f.y + 3, PointLabel::kStatic);
  s.geometry.dynamic_mask(cv::Rect(d.x, d.y, 12, 6)).setTo(255);
  const int base = s.a.area() + s.b.area() + s.c.area();

  int dropped = -1;
  const cv::Mat fused = FuseDynamicMasks({s.semantic, movable}, s.geometry, Policy(FusionPolicy::kUnion), &dropped);
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(cv::countNonZero(fused(d)), d.area());  // all of D, not only the grown corner
  EXPECT_EQ(cv::countNonZero(fused(e)), 0);         // 2 < 3 points: E stays
  EXPECT_EQ(cv::countNonZero(fused(f)), 0);
  EXPECT_EQ(cv::countNonZero(fused), base + d.area());

  FusionOptions options = Policy(FusionPolicy::kUnion);
  options.movable_dynamic_evidence = 2;  // vanished points count as evidence too
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic, movable}, s.geometry, options, &dropped)),
            base + d.area() + e.area());
  EXPECT_EQ(dropped, 2);
  // Switched off, or without geometry, or with a policy that ignores one of
  // the two: only geometry's corner of D (or nothing) goes.
  options.drop_moving_movables = false;
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic, movable}, s.geometry, options, &dropped)),
            base + 12 * 6);
  EXPECT_EQ(dropped, 0);
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic, movable}, {}, Policy(FusionPolicy::kUnion))),
            s.a.area() + s.b.area());
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic, movable}, s.geometry, Policy(FusionPolicy::kSemanticOnly))),
            s.a.area() + s.b.area());
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic, movable}, s.geometry, Policy(FusionPolicy::kGeometryOnly))),
            s.c.area() + 12 * 6);
  // geometry_confirms drops moving movables too.
  EXPECT_EQ(cv::countNonZero(FuseDynamicMasks({s.semantic, movable}, s.geometry,
                                              Policy(FusionPolicy::kGeometryConfirms))(d)),
            d.area());
}

// A still chair beside a walker: a few moving labels at its edge (parallax
// at a see-through back, the walker's outline) among many static ones, and
// moving points where the walker's mask overlaps it. It stays; a pushed one,
// whose points mostly disagree, goes.
TEST(FuseDynamicMasks, AStillMovableWithAFewMovingLabelsStays) {
  Scene s;
  const cv::Rect chair{40, 55, 50, 40};
  cv::Mat movable = cv::Mat::zeros(s.semantic.size(), CV_8UC1);
  movable(chair).setTo(255);
  for (int i = 0; i < 8; ++i) s.Add(chair.x + 5 + 5 * i, chair.y + 20, PointLabel::kStatic);
  for (int i = 0; i < 3; ++i) s.Add(chair.x + 2, chair.y + 12 + 10 * i, PointLabel::kDynamic);
  // The walker's mask reaches over the chair's top edge, with 6 moving points.
  const cv::Rect walker_edge{chair.x, chair.y, chair.width, 6};
  s.semantic(walker_edge).setTo(255);
  for (int i = 0; i < 6; ++i) s.Add(chair.x + 10 + 5 * i, chair.y + 2, PointLabel::kDynamic);

  int dropped = -1;
  cv::Mat fused = FuseDynamicMasks({s.semantic, movable}, s.geometry, Policy(FusionPolicy::kUnion), &dropped);
  EXPECT_EQ(dropped, 0);  // 3 of 11 counted points move: 0.27 < 0.5
  EXPECT_EQ(cv::countNonZero(fused(chair)), walker_edge.area());

  FusionOptions options = Policy(FusionPolicy::kUnion);
  options.movable_dynamic_share = 0.25;
  fused = FuseDynamicMasks({s.semantic, movable}, s.geometry, options, &dropped);
  EXPECT_EQ(dropped, 1);
  EXPECT_EQ(cv::countNonZero(fused(chair)), chair.area());

  // Were the walker's 6 points counted, 9 of 17 would move (0.53): the chair
  // would go at the default share. They are the walker's evidence.
  options.movable_dynamic_share = 0.5;
  FuseDynamicMasks({s.semantic, movable}, s.geometry, options, &dropped);
  EXPECT_EQ(dropped, 0);
  // Pushed: its static points now disagree too.
  for (std::size_t i = 0; i < s.geometry.labels.size(); ++i) {
    if (s.geometry.labels[i] == PointLabel::kStatic && chair.contains(cv::Point(s.geometry.points[i].pixel.x(),
                                                                                   s.geometry.points[i].pixel.y()))) {
      s.geometry.labels[i] = PointLabel::kVanished;
    }
  }
  FuseDynamicMasks({s.semantic, movable}, s.geometry, options, &dropped);
  EXPECT_EQ(dropped, 1);

  FusionOptions bad;
  bad.movable_dynamic_share = 1.5;
  EXPECT_THROW(bad.Check(), Error);
  bad.movable_dynamic_share = -0.1;
  EXPECT_THROW(bad.Check(), Error);
}

TEST(FusionPolicy, NamesRoundTrip) {
  for (const FusionPolicy p : {FusionPolicy::kUnion, FusionPolicy::kGeometryConfirms,
                               FusionPolicy::kSemanticOnly, FusionPolicy::kGeometryOnly}) {
    EXPECT_EQ(ParseFusionPolicy(ToString(p)), p);
  }
  EXPECT_THROW(ParseFusionPolicy("intersection"), Error);
}

}  // namespace
}  // namespace dlslam::dynamic
