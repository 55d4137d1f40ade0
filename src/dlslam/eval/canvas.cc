#include "dlslam/eval/canvas.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace dlslam::eval {

void Canvas::Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width) {
  const Eigen::Vector2d points[2] = {a, b};
  Polyline(points, color, width);
}

namespace {

std::string Hex(Rgb c) { return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b); }

std::string EscapeXml(std::string_view text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

cv::Scalar Bgr(Rgb c) { return cv::Scalar(c.b, c.g, c.r); }

// OpenCV draws with integer coordinates plus `kShift` fractional bits.
constexpr int kShift = 4;
cv::Point Fixed(const Eigen::Vector2d& p) {
  return cv::Point(static_cast<int>(std::lround(p.x() * (1 << kShift))),
                   static_cast<int>(std::lround(p.y() * (1 << kShift))));
}

}  // namespace

SvgCanvas::SvgCanvas(int width, int height) : width_(width), height_(height) {
  FillRect({0, 0}, {width, height}, {255, 255, 255});
}

void SvgCanvas::Polyline(std::span<const Eigen::Vector2d> points, Rgb color, double width) {
  if (points.size() < 2) return;
  body_ += "<polyline fill=\"none\" stroke=\"" + Hex(color) + "\" stroke-width=\"" +
           fmt::format("{:.2f}", width) + "\" stroke-linejoin=\"round\" points=\"";
  for (const Eigen::Vector2d& p : points) body_ += fmt::format("{:.2f},{:.2f} ", p.x(), p.y());
  body_ += "\"/>\n";
}

void SvgCanvas::Circle(const Eigen::Vector2d& center, double radius, Rgb fill) {
  body_ += fmt::format("<circle cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\" fill=\"{}\"/>\n",
                       center.x(), center.y(), radius, Hex(fill));
}

void SvgCanvas::FillRect(const Eigen::Vector2d& top_left, const Eigen::Vector2d& size, Rgb fill) {
  body_ += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"{}\"/>\n",
                       top_left.x(), top_left.y(), size.x(), size.y(), Hex(fill));
}

void SvgCanvas::Text(const Eigen::Vector2d& baseline, std::string_view text, double height,
                     Rgb color, TextAnchor anchor) {
  const char* anchor_name = anchor == TextAnchor::kStart    ? "start"
                            : anchor == TextAnchor::kMiddle ? "middle"
                                                            : "end";
  body_ += fmt::format(
      "<text x=\"{:.2f}\" y=\"{:.2f}\" font-family=\"sans-serif\" font-size=\"{:.1f}\" "
      "fill=\"{}\" text-anchor=\"{}\">{}</text>\n",
      baseline.x(), baseline.y(), height, Hex(color), anchor_name, EscapeXml(text));
}

std::string SvgCanvas::Finish() const {
  return fmt::format(
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
             "viewBox=\"0 0 {0} {1}\">\n",
             width_, height_) +
         body_ + "</svg>\n";
}

MatCanvas::MatCanvas(int width, int height)
    : image_(height, width, CV_8UC3, cv::Scalar(255, 255, 255)) {}

void MatCanvas::Polyline(std::span<const Eigen::Vector2d> points, Rgb color, double width) {
  if (points.size() < 2) return;
  std::vector<cv::Point> fixed;
  fixed.reserve(points.size());
  for (const Eigen::Vector2d& p : points) fixed.push_back(Fixed(p));
  const int thickness = std::max(1, static_cast<int>(std::lround(width)));
  cv::polylines(image_, fixed, false, Bgr(color), thickness, cv::LINE_AA, kShift);
}

void MatCanvas::Circle(const Eigen::Vector2d& center, double radius, Rgb fill) {
  cv::circle(image_, Fixed(center), static_cast<int>(std::lround(radius * (1 << kShift))), Bgr(fill),
             cv::FILLED, cv::LINE_AA, kShift);
}

void MatCanvas::FillRect(const Eigen::Vector2d& top_left, const Eigen::Vector2d& size, Rgb fill) {
  const Eigen::Vector2d bottom_right = top_left + size;
  cv::rectangle(image_, cv::Point(static_cast<int>(std::lround(top_left.x())),
                                  static_cast<int>(std::lround(top_left.y()))),
                cv::Point(static_cast<int>(std::lround(bottom_right.x())) - 1,
                          static_cast<int>(std::lround(bottom_right.y())) - 1),
                Bgr(fill), cv::FILLED);
}

void MatCanvas::Text(const Eigen::Vector2d& baseline, std::string_view text, double height,
                     Rgb color, TextAnchor anchor) {
  // Hershey simplex capitals are ~22 px tall at scale 1; SVG font-size is
  // about 1.4 cap heights.
  const double scale = height / 1.4 / 22.0;
  const int thickness = height >= 18 ? 2 : 1;
  const std::string s(text);
  int baseline_offset = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline_offset);
  double x = baseline.x();
  if (anchor == TextAnchor::kMiddle) x -= size.width / 2.0;
  if (anchor == TextAnchor::kEnd) x -= size.width;
  cv::putText(image_, s, cv::Point(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(baseline.y()))),
              cv::FONT_HERSHEY_SIMPLEX, scale, Bgr(color), thickness, cv::LINE_AA);
}

}  // namespace dlslam::eval
