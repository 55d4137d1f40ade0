#include "dlslam/eval/plot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>

#include "dlslam/eval/plot_axes.h"
#include "dlslam/util/check.h"

namespace dlslam::eval {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

AteResult SomeAte(int n) {
  AteResult r;
  std::vector<double> errors;
  for (int k = 0; k < n; ++k) {
    AtePair p;
    p.gt_timestamp = 100.0 + 0.1 * k;
    p.est_timestamp = p.gt_timestamp;
    p.gt_position = Eigen::Vector3d(std::cos(0.1 * k), std::sin(0.1 * k), 0.01 * k);
    p.est_position_aligned = p.gt_position + Eigen::Vector3d(0.02 * std::sin(k), 0, 0.01);
    p.error = (p.est_position_aligned - p.gt_position).norm();
    errors.push_back(p.error);
    r.per_pair.push_back(p);
  }
  r.pairs = r.per_pair.size();
  r.error = ComputeErrorStats(errors);
  return r;
}

RpeResult SomeRpe(int n) {
  RpeResult r;
  for (int k = 0; k < n; ++k) {
    RpePair p;
    p.est_timestamp_0 = 50.0 + 0.033 * k;
    p.translation_error = 0.01 + 0.005 * std::sin(0.2 * k);
    p.rotation_error_deg = 0.5 + 0.2 * std::cos(0.3 * k);
    r.per_pair.push_back(p);
  }
  r.pairs = r.per_pair.size();
  return r;
}

TEST(PlotTest, AteSvgDrawsEveryPoseInBothViews) {
  const std::string svg = AtePlotSvg(SomeAte(40));
  EXPECT_TRUE(svg.starts_with("<?xml"));
  EXPECT_THAT(svg, HasSubstr("<svg xmlns=\"http://www.w3.org/2000/svg\""));
  EXPECT_TRUE(svg.ends_with("</svg>\n"));
  EXPECT_EQ(Count(svg, "<circle"), 80u);
  for (const char* text : {"top view (x-y)", "side view (x-z)", "error over time", "error [m]"}) {
    EXPECT_THAT(svg, HasSubstr(text));
  }
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
  EXPECT_THAT(svg, Not(HasSubstr("inf")));
}

TEST(PlotTest, AteImageIsDrawnInColour) {
  const cv::Mat image = AtePlotImage(SomeAte(40));
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.cols, 1200);
  EXPECT_EQ(image.rows, 900);
  int coloured = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - p[2]) > 60) ++coloured;  // not grey: the error colours
    }
  }
  EXPECT_GT(coloured, 500);
}

TEST(PlotTest, RpePlotsBothErrors) {
  const std::string svg = RpePlotSvg(SomeRpe(100));
  EXPECT_THAT(svg, HasSubstr("translation error"));
  EXPECT_THAT(svg, HasSubstr("rotation error"));
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
  const cv::Mat image = RpePlotImage(SomeRpe(100));
  EXPECT_EQ(image.type(), CV_8UC3);
  EXPECT_LT(cv::mean(image)[0], 254.0);  // something drawn
}

TEST(PlotTest, FlatErrorsDoNotBreakTheScales) {
  AteResult r = SomeAte(3);
  for (AtePair& p : r.per_pair) {
    p.est_position_aligned = p.gt_position;
    p.error = 0.0;
  }
  r.error = ErrorStats{};
  const std::string svg = AtePlotSvg(r);
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
  EXPECT_THAT(svg, Not(HasSubstr("inf")));
}

TEST(PlotTest, PngEncodingRoundTrips) {
  const cv::Mat image = RpePlotImage(SomeRpe(10));
  const std::vector<unsigned char> png = EncodePng(image);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png[1], 'P');
  const cv::Mat back = cv::imdecode(png, cv::IMREAD_COLOR);
  EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0);
  EXPECT_THROW(EncodePng(cv::Mat()), Error);
}

TEST(PlotTest, FormatFollowsTheExtension) {
  EXPECT_EQ(PlotFormatFromPath("a/b.svg"), PlotFormat::kSvg);
  EXPECT_EQ(PlotFormatFromPath("b.PNG"), PlotFormat::kPng);
  EXPECT_THROW(PlotFormatFromPath("b.jpg"), Error);
  EXPECT_THROW(PlotFormatFromPath("noext"), Error);
}

TEST(PlotAxesTest, NiceTicksAreRoundAndInside) {
  const std::vector<double> t = NiceTicks({-0.13, 1.07}, 6);
  ASSERT_FALSE(t.empty());
  EXPECT_GE(t.front(), -0.13);
  EXPECT_LE(t.back(), 1.07);
  EXPECT_NEAR(t[1] - t[0], 0.2, 1e-12);
  EXPECT_EQ(TickLabel(0.4, 0.2), "0.4");
  EXPECT_EQ(TickLabel(-1e-17, 0.2), "0.0");
  EXPECT_EQ(TickLabel(1500, 500), "1500");
}

}  // namespace
}  // namespace dlslam::eval
