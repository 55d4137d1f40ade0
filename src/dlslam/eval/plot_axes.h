#pragma once
// Axes, ticks and the error colour scale shared by the evaluation plots.

#include <Eigen/Core>

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dlslam/eval/canvas.h"

namespace dlslam::eval {

struct Range {
  double min = 0.0;
  double max = 1.0;
};

struct PixelRect {
  double x = 0.0;  // left
  double y = 0.0;  // top
  double width = 1.0;
  double height = 1.0;
};

// The range of values, padded by `padding` of its width on both sides; a
// flat or empty range becomes a unit-wide one around its value.
Range RangeOf(std::span<const double> values, double padding = 0.05);

// About `count` round tick values (1, 2, 5 times a power of ten) inside range.
std::vector<double> NiceTicks(const Range& range, int count);

// A tick label with as many decimals as the tick step needs.
std::string TickLabel(double value, double step);

// Maps data coordinates into a pixel rectangle (y up in data, down in pixels).
class Axes {
 public:
  // With equal_aspect the ranges grow so that a metre is as long on x as on y.
  Axes(const PixelRect& rect, Range x, Range y, bool equal_aspect);

  Eigen::Vector2d ToPixel(double x, double y) const;
  const Range& x_range() const { return x_; }
  const Range& y_range() const { return y_; }

  // Frame, grid, ticks and labels.
  void Draw(Canvas& canvas, std::string_view title, std::string_view x_label,
            std::string_view y_label) const;

 private:
  PixelRect rect_;
  Range x_;
  Range y_;
};

// Colour for a fraction in [0, 1] of the error scale (blue - green - yellow - red).
Rgb ErrorColor(double fraction);

// A vertical colour bar for `values` with ticks and a label.
void DrawColorBar(Canvas& canvas, const PixelRect& rect, const Range& values, std::string_view label);

}  // namespace dlslam::eval
