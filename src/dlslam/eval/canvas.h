#pragma once
// A minimal 2D drawing surface (pixels, y down) with two back ends, so that
// one layout function draws both the SVG and the PNG form of a plot.

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace dlslam::eval {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
};

enum class TextAnchor { kStart, kMiddle, kEnd };

class Canvas {
 public:
  virtual ~Canvas() = default;
  virtual void Polyline(std::span<const Eigen::Vector2d> points, Rgb color, double width) = 0;
  virtual void Circle(const Eigen::Vector2d& center, double radius, Rgb fill) = 0;
  virtual void FillRect(const Eigen::Vector2d& top_left, const Eigen::Vector2d& size, Rgb fill) = 0;
  // `baseline` is the left / centre / right end of the text's baseline.
  virtual void Text(const Eigen::Vector2d& baseline, std::string_view text, double height, Rgb color,
                    TextAnchor anchor = TextAnchor::kStart) = 0;

  void Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Rgb color, double width);
};

// Collects SVG elements; Finish() returns the document.
class SvgCanvas final : public Canvas {
 public:
  SvgCanvas(int width, int height);
  void Polyline(std::span<const Eigen::Vector2d> points, Rgb color, double width) override;
  void Circle(const Eigen::Vector2d& center, double radius, Rgb fill) override;
  void FillRect(const Eigen::Vector2d& top_left, const Eigen::Vector2d& size, Rgb fill) override;
  void Text(const Eigen::Vector2d& baseline, std::string_view text, double height, Rgb color,
            TextAnchor anchor) override;
  std::string Finish() const;

 private:
  int width_;
  int height_;
  std::string body_;
};

// Draws into a white 8-bit BGR image with OpenCV (anti-aliased).
class MatCanvas final : public Canvas {
 public:
  MatCanvas(int width, int height);
  void Polyline(std::span<const Eigen::Vector2d> points, Rgb color, double width) override;
  void Circle(const Eigen::Vector2d& center, double radius, Rgb fill) override;
  void FillRect(const Eigen::Vector2d& top_left, const Eigen::Vector2d& size, Rgb fill) override;
  void Text(const Eigen::Vector2d& baseline, std::string_view text, double height, Rgb color,
            TextAnchor anchor) override;
  const cv::Mat& image() const { return image_; }

 private:
  cv::Mat image_;
};

}  // namespace dlslam::eval
