#include "dlslam/eval/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <opencv2/imgcodecs.hpp>

#include "dlslam/eval/canvas.h"
#include "dlslam/eval/plot_axes.h"
#include "dlslam/util/check.h"

namespace dlslam::eval {

namespace {

constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGroundTruth{120, 120, 120};
constexpr Rgb kRmse{200, 30, 30};
constexpr int kAteWidth = 1200;
constexpr int kAteHeight = 900;
constexpr int kRpeWidth = 1200;
constexpr int kRpeHeight = 760;

// One view of the aligned trajectory: ground truth as a line, the estimate
// as dots coloured by error.
void DrawTrajectoryView(Canvas& canvas, const AteResult& r, const PixelRect& rect, int axis_x,
                        int axis_y, const Range& errors, std::string_view title) {
  std::vector<double> xs;
  std::vector<double> ys;
  for (const AtePair& p : r.per_pair) {
    for (const Eigen::Vector3d* v : {&p.gt_position, &p.est_position_aligned}) {
      xs.push_back((*v)[axis_x]);
      ys.push_back((*v)[axis_y]);
    }
  }
  const Axes axes(rect, RangeOf(xs), RangeOf(ys), /*equal_aspect=*/true);
  const char* names = "xyz";
  axes.Draw(canvas, title, fmt::format("{} [m]", names[axis_x]), fmt::format("{} [m]", names[axis_y]));
  std::vector<Eigen::Vector2d> gt_line;
  for (const AtePair& p : r.per_pair) gt_line.push_back(axes.ToPixel(p.gt_position[axis_x], p.gt_position[axis_y]));
  canvas.Polyline(gt_line, kGroundTruth, 1.5);
  const double span = errors.max - errors.min;
  for (const AtePair& p : r.per_pair) {
    const double f = span > 0 ? (p.error - errors.min) / span : 0.0;
    canvas.Circle(axes.ToPixel(p.est_position_aligned[axis_x], p.est_position_aligned[axis_y]), 2.5,
                  ErrorColor(f));
  }
}

// A time series (t relative to t0) with an optional horizontal reference line.
void DrawSeries(Canvas& canvas, const PixelRect& rect, const std::vector<double>& t,
                const std::vector<double>& v, double rmse, std::string_view title,
                std::string_view y_label) {
  Range y = RangeOf(v);
  y.min = std::min(y.min, 0.0);
  const Axes axes(rect, RangeOf(t, 0.01), y, /*equal_aspect=*/false);
  axes.Draw(canvas, title, "time [s]", y_label);
  std::vector<Eigen::Vector2d> line;
  for (std::size_t k = 0; k < t.size(); ++k) line.push_back(axes.ToPixel(t[k], v[k]));
  canvas.Polyline(line, {40, 60, 200}, 1.2);
  const Eigen::Vector2d a = axes.ToPixel(axes.x_range().min, rmse);
  const Eigen::Vector2d b = axes.ToPixel(axes.x_range().max, rmse);
  canvas.Line(a, b, kRmse, 1.0);
  // Above the frame's right end, clear of the data.
  const Eigen::Vector2d corner = axes.ToPixel(axes.x_range().max, axes.y_range().max);
  canvas.Text({corner.x(), corner.y() - 8}, fmt::format("rmse {:.4g}", rmse), 13.0, kRmse,
              TextAnchor::kEnd);
}

void DrawAte(Canvas& canvas, const AteResult& r) {
  canvas.Text({kAteWidth / 2.0, 28}, fmt::format("ATE: {} pairs, rmse {:.4f} m, max {:.4f} m",
                                                 r.pairs, r.error.rmse, r.error.max),
              18.0, kBlack, TextAnchor::kMiddle);
  const Range errors{r.error.min, r.error.max};
  DrawTrajectoryView(canvas, r, {80, 90, 470, 420}, 0, 1, errors, "top view (x-y)");
  DrawTrajectoryView(canvas, r, {620, 90, 470, 420}, 0, 2, errors, "side view (x-z)");
  DrawColorBar(canvas, {1120, 90, 18, 420}, errors, "error [m]");
  std::vector<double> t;
  std::vector<double> e;
  for (const AtePair& p : r.per_pair) {
    t.push_back(p.gt_timestamp - r.per_pair.front().gt_timestamp);
    e.push_back(p.error);
  }
  DrawSeries(canvas, {80, 620, 1010, 210}, t, e, r.error.rmse, "error over time", "error [m]");
}

void DrawRpe(Canvas& canvas, const RpeResult& r) {
  canvas.Text({kRpeWidth / 2.0, 28}, fmt::format("RPE: {} pairs, rmse {:.4f} m, {:.4f} deg", r.pairs,
                                                 r.translation.rmse, r.rotation_deg.rmse),
              18.0, kBlack, TextAnchor::kMiddle);
  std::vector<double> t;
  std::vector<double> trans;
  std::vector<double> rot;
  for (const RpePair& p : r.per_pair) {
    t.push_back(p.est_timestamp_0 - r.per_pair.front().est_timestamp_0);
    trans.push_back(p.translation_error);
    rot.push_back(p.rotation_error_deg);
  }
  DrawSeries(canvas, {90, 90, 1040, 250}, t, trans, r.translation.rmse, "translation error",
             "error [m]");
  DrawSeries(canvas, {90, 450, 1040, 250}, t, rot, r.rotation_deg.rmse, "rotation error",
             "error [deg]");
}

}  // namespace

PlotFormat PlotFormatFromPath(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") return PlotFormat::kSvg;
  if (ext == ".png") return PlotFormat::kPng;
  throw Error(fmt::format("plot '{}': unknown extension '{}', expected .svg or .png", path.string(),
                          path.extension().string()));
}

std::string AtePlotSvg(const AteResult& result) {
  SvgCanvas canvas(kAteWidth, kAteHeight);
  DrawAte(canvas, result);
  return canvas.Finish();
}

cv::Mat AtePlotImage(const AteResult& result) {
  MatCanvas canvas(kAteWidth, kAteHeight);
  DrawAte(canvas, result);
  return canvas.image();
}

std::string RpePlotSvg(const RpeResult& result) {
  SvgCanvas canvas(kRpeWidth, kRpeHeight);
  DrawRpe(canvas, result);
  return canvas.Finish();
}

cv::Mat RpePlotImage(const RpeResult& result) {
  MatCanvas canvas(kRpeWidth, kRpeHeight);
  DrawRpe(canvas, result);
  return canvas.image();
}

std::vector<unsigned char> EncodePng(const cv::Mat& image) {
  std::vector<unsigned char> bytes;
  DLSLAM_CHECK(!image.empty() && image.depth() == CV_8U, "PNG needs a non-empty 8-bit image");
  if (!cv::imencode(".png", image, bytes)) throw Error("PNG encoding failed");
  return bytes;
}

}  // namespace dlslam::eval
