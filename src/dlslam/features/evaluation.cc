#include "dlslam/features/evaluation.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

cv::Point2d Apply(const cv::Matx23d& m, const cv::Point2f& p) {
  return {m(0, 0) * p.x + m(0, 1) * p.y + m(0, 2), m(1, 0) * p.x + m(1, 1) * p.y + m(1, 2)};
}

bool IsValid(const cv::Mat& valid, const cv::Point2d& p) {
  const int x = static_cast<int>(std::lround(p.x)), y = static_cast<int>(std::lround(p.y));
  return x >= 0 && y >= 0 && x < valid.cols && y < valid.rows && valid.at<uchar>(y, x) != 0;
}

double Ratio(int num, int den) { return den > 0 ? static_cast<double>(num) / den : 0.0; }

}  // namespace

WarpedImage WarpImage(const cv::Mat& source, double angle_deg, double scale, int margin) {
  DLSLAM_CHECK(!source.empty() && scale > 0, "WarpImage: empty source or scale {}", scale);
  const cv::Point2f centre(0.5f * static_cast<float>(source.cols - 1),
                           0.5f * static_cast<float>(source.rows - 1));
  cv::Matx23d m = cv::getRotationMatrix2D(centre, angle_deg, scale);
  // Canvas: the bounding box of the transformed image.
  const cv::Rect2f box =
      cv::RotatedRect(centre, cv::Size2f(static_cast<float>(source.cols * scale),
                                         static_cast<float>(source.rows * scale)),
                      static_cast<float>(angle_deg))
          .boundingRect2f();
  const cv::Size canvas(static_cast<int>(std::ceil(box.width)), static_cast<int>(std::ceil(box.height)));
  m(0, 2) += 0.5 * (canvas.width - 1) - centre.x;
  m(1, 2) += 0.5 * (canvas.height - 1) - centre.y;

  WarpedImage out;
  out.to_warped = m;
  cv::warpAffine(source, out.image, m, canvas, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  const cv::Mat ones(source.size(), CV_8UC1, cv::Scalar(255));
  cv::warpAffine(ones, out.valid, m, canvas, cv::INTER_NEAREST, cv::BORDER_CONSTANT);
  if (margin > 0) {
    cv::erode(out.valid, out.valid,
              cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * margin + 1, 2 * margin + 1)));
  }
  return out;
}

double TransformScores::repeatability() const { return Ratio(repeated, keypoints_a); }
double TransformScores::chance_repeatability() const {
  return keypoints_a > 0 ? repeated_by_chance / keypoints_a : 0.0;
}
double TransformScores::precision() const { return Ratio(correct_matches, matches); }
double TransformScores::recall() const { return Ratio(correct_matches, repeated); }

TransformScores ScoreUnderTransform(const Features& a, const Features& b, const WarpedImage& warp,
                                    double tolerance_px, const MatchOptions& match_options) {
  const double tol2 = tolerance_px * tolerance_px;
  // Only keypoints in the common area count, with their rows kept for matching.
  std::vector<int> rows_a, rows_b;
  std::vector<cv::Point2d> mapped_a;
  for (int i = 0; i < static_cast<int>(a.keypoints.size()); ++i) {
    const cv::Point2d p = Apply(warp.to_warped, a.keypoints[static_cast<size_t>(i)].pt);
    if (!IsValid(warp.valid, p)) continue;
    rows_a.push_back(i);
    mapped_a.push_back(p);
  }
  for (int j = 0; j < static_cast<int>(b.keypoints.size()); ++j) {
    if (IsValid(warp.valid, b.keypoints[static_cast<size_t>(j)].pt)) rows_b.push_back(j);
  }
  TransformScores s;
  s.keypoints_a = static_cast<int>(rows_a.size());
  s.keypoints_b = static_cast<int>(rows_b.size());
  const auto near = [&](const cv::Point2d& p, int j) {
    const cv::Point2f& q = b.keypoints[static_cast<size_t>(j)].pt;
    return (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) <= tol2;
  };
  const auto has_neighbour = [&](const cv::Point2d& p) {
    return std::any_of(rows_b.begin(), rows_b.end(), [&](int j) { return near(p, j); });
  };
  for (const cv::Point2d& p : mapped_a) {
    s.repeated += has_neighbour(p);
    for (const cv::Point2d shift : {cv::Point2d(14, 14), cv::Point2d(-14, 14), cv::Point2d(14, -14),
                                    cv::Point2d(-14, -14)}) {
      s.repeated_by_chance += 0.25 * has_neighbour(p + shift);
    }
  }
  cv::Mat desc_a(static_cast<int>(rows_a.size()), a.descriptors.cols, a.descriptors.type());
  cv::Mat desc_b(static_cast<int>(rows_b.size()), b.descriptors.cols, b.descriptors.type());
  for (size_t i = 0; i < rows_a.size(); ++i) a.descriptors.row(rows_a[i]).copyTo(desc_a.row(static_cast<int>(i)));
  for (size_t j = 0; j < rows_b.size(); ++j) b.descriptors.row(rows_b[j]).copyTo(desc_b.row(static_cast<int>(j)));
  for (const cv::DMatch& m : MatchBruteForce(desc_a, desc_b, match_options)) {
    ++s.matches;
    if (near(mapped_a[static_cast<size_t>(m.queryIdx)], rows_b[static_cast<size_t>(m.trainIdx)])) {
      ++s.correct_matches;
    }
  }
  return s;
}

}  // namespace dlslam::features
