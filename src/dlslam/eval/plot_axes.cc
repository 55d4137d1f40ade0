#include "dlslam/eval/plot_axes.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace dlslam::eval {

namespace {
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrid{225, 225, 225};
constexpr double kFont = 13.0;
}  // namespace

Range RangeOf(std::span<const double> values, double padding) {
  if (values.empty()) return {0.0, 1.0};
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  Range r{*lo, *hi};
  const double width = r.max - r.min;
  if (!(width > 0.0)) return {r.min - 0.5, r.max + 0.5};
  return {r.min - padding * width, r.max + padding * width};
}

std::vector<double> NiceTicks(const Range& range, int count) {
  const double span = range.max - range.min;
  if (!(span > 0.0) || count < 1) return {range.min};
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw * (1.0 - 1e-9)) break;  // 1.2 / 6 is 0.2000...04
  }
  std::vector<double> ticks;
  for (double k = std::ceil(range.min / step); k * step <= range.max + 1e-9 * step; k += 1.0) {
    ticks.push_back(k * step);
  }
  return ticks;
}

std::string TickLabel(double value, double step) {
  const int decimals = std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 9);
  if (std::abs(value) < step * 1e-6) value = 0.0;  // no "-0.00"
  return fmt::format("{:.{}f}", value, decimals);
}

Axes::Axes(const PixelRect& rect, Range x, Range y, bool equal_aspect) : rect_(rect), x_(x), y_(y) {
  if (!equal_aspect) return;
  const double per_px = std::max((x_.max - x_.min) / rect_.width, (y_.max - y_.min) / rect_.height);
  const double x_mid = (x_.min + x_.max) / 2.0;
  const double y_mid = (y_.min + y_.max) / 2.0;
  x_ = {x_mid - per_px * rect_.width / 2.0, x_mid + per_px * rect_.width / 2.0};
  y_ = {y_mid - per_px * rect_.height / 2.0, y_mid + per_px * rect_.height / 2.0};
}

Eigen::Vector2d Axes::ToPixel(double x, double y) const {
  return {rect_.x + (x - x_.min) / (x_.max - x_.min) * rect_.width,
          rect_.y + rect_.height - (y - y_.min) / (y_.max - y_.min) * rect_.height};
}

void Axes::Draw(Canvas& canvas, std::string_view title, std::string_view x_label,
                std::string_view y_label) const {
  const double left = rect_.x;
  const double right = rect_.x + rect_.width;
  const double top = rect_.y;
  const double bottom = rect_.y + rect_.height;
  const std::vector<double> x_ticks = NiceTicks(x_, 6);
  const std::vector<double> y_ticks = NiceTicks(y_, 5);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1.0;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1.0;
  for (const double t : x_ticks) {
    const double px = ToPixel(t, y_.min).x();
    canvas.Line({px, top}, {px, bottom}, kGrid, 1.0);
    canvas.Line({px, bottom}, {px, bottom + 5}, kBlack, 1.0);
    canvas.Text({px, bottom + 19}, TickLabel(t, x_step), kFont, kBlack, TextAnchor::kMiddle);
  }
  for (const double t : y_ticks) {
    const double py = ToPixel(x_.min, t).y();
    canvas.Line({left, py}, {right, py}, kGrid, 1.0);
    canvas.Line({left - 5, py}, {left, py}, kBlack, 1.0);
    canvas.Text({left - 8, py + 4}, TickLabel(t, y_step), kFont, kBlack, TextAnchor::kEnd);
  }
  const Eigen::Vector2d frame[5] = {{left, top}, {right, top}, {right, bottom}, {left, bottom}, {left, top}};
  canvas.Polyline(frame, kBlack, 1.0);
  canvas.Text({(left + right) / 2, top - 8}, title, 15.0, kBlack, TextAnchor::kMiddle);
  canvas.Text({(left + right) / 2, bottom + 38}, x_label, kFont, kBlack, TextAnchor::kMiddle);
  // Horizontal: rotated text is not available in every back end.
  canvas.Text({left, top - 26}, y_label, kFont, kBlack, TextAnchor::kStart);
}

Rgb ErrorColor(double fraction) {
  static constexpr double kStops[5][3] = {
      {40, 60, 200}, {30, 170, 220}, {60, 190, 80}, {240, 200, 40}, {215, 40, 30}};
  const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0) * 4.0;
  const int k = std::min(3, static_cast<int>(f));
  const double w = f - k;
  const auto mix = [&](int c) {
    return static_cast<std::uint8_t>(std::lround(kStops[k][c] * (1 - w) + kStops[k + 1][c] * w));
  };
  return {mix(0), mix(1), mix(2)};
}

void DrawColorBar(Canvas& canvas, const PixelRect& rect, const Range& values, std::string_view label) {
  constexpr int kSteps = 64;
  const double step_h = rect.height / kSteps;
  for (int s = 0; s < kSteps; ++s) {
    const double fraction = (s + 0.5) / kSteps;
    canvas.FillRect({rect.x, rect.y + rect.height - (s + 1) * step_h}, {rect.width, step_h + 0.5},
                    ErrorColor(fraction));
  }
  const double span = values.max - values.min;
  const std::vector<double> ticks = NiceTicks(values, 5);
  const double tick_step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  for (const double t : ticks) {
    const double py = rect.y + rect.height - (span > 0 ? (t - values.min) / span : 0.0) * rect.height;
    canvas.Line({rect.x + rect.width, py}, {rect.x + rect.width + 4, py}, kBlack, 1.0);
    canvas.Text({rect.x + rect.width + 7, py + 4}, TickLabel(t, tick_step), kFont, kBlack);
  }
  canvas.Text({rect.x + rect.width / 2, rect.y - 16}, label, kFont, kBlack, TextAnchor::kMiddle);
}

}  // namespace dlslam::eval
