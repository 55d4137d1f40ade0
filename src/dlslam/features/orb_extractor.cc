#include "dlslam/features/orb_extractor.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "dlslam/features/orientation.h"
#include "dlslam/features/quadtree.h"
#include "dlslam/util/check.h"

namespace dlslam::features {

namespace {

// The level-0 (exclusion mask) coordinate of a level's pixel coordinate.
int MaskCoordinate(int level_coordinate, double scale, int mask_size) {
  return std::min(static_cast<int>(std::lround(level_coordinate * scale)), mask_size - 1);
}

void CheckExclusionMask(const cv::Mat& mask, cv::Size size) {
  DLSLAM_CHECK(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == size),
               "exclusion mask must be CV_8UC1 {}x{}, got {} {}x{}", size.width, size.height,
               cv::typeToString(mask.type()), mask.cols, mask.rows);
}

}  // namespace

OrbExtractor::OrbExtractor(const OrbOptions& options, std::span<const PatternTest> pattern)
    : options_((options.Check(), options)), brief_(pattern) {
  level_scales_ = LevelScales(options_);
  level_targets_ = LevelFeatureTargets(options_);
  blur_kernel_ = cv::getGaussianKernel(7, 2.0, CV_32F);
  const auto n = static_cast<size_t>(options_.n_levels);
  pyramid_.resize(n);
  smoothed_.resize(n);
  level_corners_.resize(n);
  detected_.resize(n);
  described_.resize(n);
}

OrbFeatures OrbExtractor::Extract(const cv::Mat& image, const cv::Mat& exclusion_mask) {
  OrbFeatures out;
  Extract(image, exclusion_mask, out);
  return out;
}

void OrbExtractor::BuildPyramid(const cv::Mat& grey) {
  pyramid_[0] = grey;
  for (size_t level = 1; level < pyramid_.size(); ++level) {
    const cv::Size size(static_cast<int>(std::lround(grey.cols / level_scales_[level])),
                        static_cast<int>(std::lround(grey.rows / level_scales_[level])));
    // Levels without room for a keypoint stay empty (and get none).
    if (size.width <= 2 * options_.edge_border || size.height <= 2 * options_.edge_border) {
      pyramid_[level].release();
      continue;
    }
    cv::resize(pyramid_[level - 1], pyramid_[level], size, 0, 0, cv::INTER_LINEAR);
  }
}

void OrbExtractor::DetectLevel(int level, const cv::Mat& exclusion_mask) {
  const auto l = static_cast<size_t>(level);
  detected_[l].clear();
  const cv::Mat& image = pyramid_[l];
  if (image.empty()) return;
  const int border = options_.edge_border;
  const cv::Rect area(border, border, image.cols - 2 * border, image.rows - 2 * border);
  const GridFastParams fast{options_.fast_threshold_initial, options_.fast_threshold_min,
                            options_.cell_size};
  const double scale = level_scales_[l];
  // A level pixel looks the (level-0) exclusion mask up here.
  const auto mask_x = [&](int x) { return MaskCoordinate(x, scale, exclusion_mask.cols); };
  const auto mask_y = [&](int y) { return MaskCoordinate(y, scale, exclusion_mask.rows); };
  // Cells wholly inside the exclusion mask are not searched: in a crowd
  // that is a third of the image or more.
  std::vector<bool> skip_cells;
  if (!exclusion_mask.empty()) {
    const FastGrid grid(area, options_.cell_size);
    skip_cells.resize(static_cast<size_t>(grid.size()));
    for (int row = 0; row < grid.rows; ++row) {
      for (int col = 0; col < grid.cols; ++col) {
        const cv::Rect cell = grid.Cell(row, col);
        // Every pixel of the cell looks the mask up inside this box.
        const int x0 = mask_x(cell.x), x1 = mask_x(cell.x + cell.width - 1) + 1;
        const int y0 = mask_y(cell.y), y1 = mask_y(cell.y + cell.height - 1) + 1;
        const int excluded = excluded_integral_.at<int>(y1, x1) - excluded_integral_.at<int>(y0, x1) -
                             excluded_integral_.at<int>(y1, x0) + excluded_integral_.at<int>(y0, x0);
        skip_cells[static_cast<size_t>(grid.Index(row, col))] = excluded == 255 * (x1 - x0) * (y1 - y0);
      }
    }
  }
  DetectGridFast(image, area, fast, fast_scratch_, detected_[l], skip_cells);
}

void OrbExtractor::SelectLevel(int level, const cv::Mat& exclusion_mask) {
  const auto l = static_cast<size_t>(level);
  std::vector<FastCorner>& corners = level_corners_[l];
  corners = detected_[l];
  const cv::Mat& image = pyramid_[l];
  if (image.empty()) return;
  if (!exclusion_mask.empty()) {
    const double scale = level_scales_[l];
    // The level's box of +-exclusion_radius px, in level-0 mask pixels.
    const int reach = static_cast<int>(std::ceil(options_.exclusion_radius * scale));
    std::erase_if(corners, [&](const FastCorner& c) {
      const int x = MaskCoordinate(c.x, scale, exclusion_mask.cols);
      const int y = MaskCoordinate(c.y, scale, exclusion_mask.rows);
      if (reach == 0) return exclusion_mask.at<uchar>(y, x) != 0;
      const int x0 = std::max(x - reach, 0), x1 = std::min(x + reach + 1, exclusion_mask.cols);
      const int y0 = std::max(y - reach, 0), y1 = std::min(y + reach + 1, exclusion_mask.rows);
      return excluded_integral_.at<int>(y1, x1) - excluded_integral_.at<int>(y0, x1) -
                 excluded_integral_.at<int>(y1, x0) + excluded_integral_.at<int>(y0, x0) !=
             0;
    });
  }
  const int border = options_.edge_border;
  const cv::Rect area(border, border, image.cols - 2 * border, image.rows - 2 * border);
  DistributeQuadtree(area, level_targets_[l], corners);
}

void OrbExtractor::PrepareImage(const cv::Mat& image) {
  if (borrowed_) {  // never write into another extractor's levels
    for (cv::Mat& level : pyramid_) level.release();
    for (cv::Mat& level : smoothed_) level.release();
    borrowed_ = false;
  }
  DLSLAM_CHECK(!image.empty(), "ORB extraction needs a non-empty image");
  DLSLAM_CHECK(image.depth() == CV_8U && (image.channels() == 1 || image.channels() == 3 ||
                                          image.channels() == 4),
               "ORB extraction needs an 8-bit grey or BGR(A) image, got {} (depth {}, {} channels)",
               cv::typeToString(image.type()), image.depth(), image.channels());
  const int min_side = 2 * options_.edge_border + 1;
  DLSLAM_CHECK(image.cols >= min_side && image.rows >= min_side,
               "image {}x{} too small for ORB: needs {} px or more on each side (edge border {})",
               image.cols, image.rows, min_side, options_.edge_border);
  if (image.channels() == 1) {
    BuildPyramid(image);
  } else {
    cv::cvtColor(image, grey_, image.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY);
    BuildPyramid(grey_);
  }
}

void OrbExtractor::SmoothLevel(size_t level) {
  // 7x7 Gaussian, sigma 2. sepFilter2D rather than GaussianBlur: OpenCV
  // 4.6's bit-exact 8-bit GaussianBlur path is about 25% slower here.
  cv::sepFilter2D(pyramid_[level], smoothed_[level], CV_8U, blur_kernel_, blur_kernel_,
                  cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT_101);
}

void OrbExtractor::SetExclusion(const cv::Mat& exclusion_mask) {
  CheckExclusionMask(exclusion_mask, extracted_size_);
  if (exclusion_mask.empty()) {
    excluded_.release();
    return;
  }
  cv::compare(exclusion_mask, 0, excluded_, cv::CMP_NE);  // 255 where excluded
  cv::integral(excluded_, excluded_integral_, CV_32S);
}

void OrbExtractor::Extract(const cv::Mat& image, const cv::Mat& exclusion_mask,
                           OrbFeatures& out) {
  CheckExclusionMask(exclusion_mask, image.size());  // before anything is changed
  extracted_size_ = cv::Size();  // until the pyramid and corners are this image's
  PrepareImage(image);
  extracted_size_ = image.size();
  for (cv::Mat& level : smoothed_) level.release();
  for (std::vector<Described>& level : described_) level.clear();
  DetectSelectDescribe(exclusion_mask, out, nullptr);
}

void OrbExtractor::DetectSelectDescribe(const cv::Mat& exclusion_mask, OrbFeatures& out,
                                        const OrbExtractor* known) {
  SetExclusion(exclusion_mask);
  for (int level = 0; level < options_.n_levels; ++level) {
    DetectLevel(level, exclusion_mask);
    SelectLevel(level, exclusion_mask);
  }
  detected_exclusion_ = excluded_.clone();
  Describe(out, known);
}

bool OrbExtractor::CanExtractOn(const OrbExtractor& source) const {
  return source.options_.n_levels == options_.n_levels && source.options_.scale_factor == options_.scale_factor &&
         source.options_.edge_border == options_.edge_border;
}

OrbFeatures OrbExtractor::ExtractOn(const OrbExtractor& source, const cv::Mat& exclusion_mask) {
  DLSLAM_CHECK(CanExtractOn(source),
               "OrbExtractor::ExtractOn: pyramids differ (levels {} / {}, scale {} / {}, edge border {} / {})",
               options_.n_levels, source.options_.n_levels, options_.scale_factor, source.options_.scale_factor,
               options_.edge_border, source.options_.edge_border);
  DLSLAM_CHECK(!source.extracted_size_.empty(), "OrbExtractor::ExtractOn needs an Extract call of the source first");
  pyramid_ = source.pyramid_;  // headers: the pixels are shared
  smoothed_ = source.smoothed_;
  borrowed_ = true;
  extracted_size_ = source.extracted_size_;
  for (std::vector<Described>& level : described_) level.clear();
  OrbFeatures out;
  DetectSelectDescribe(exclusion_mask, out, brief_ == source.brief_ ? &source : nullptr);
  return out;
}

OrbFeatures OrbExtractor::Reextract(const cv::Mat& exclusion_mask) {
  DLSLAM_CHECK(!extracted_size_.empty(), "OrbExtractor::Reextract needs an Extract call first");
  SetExclusion(exclusion_mask);
  // The first extraction's corners hold every corner outside the new mask
  // when that mask covers the first one: cells skipped then are inside it
  // now, and FAST's per-cell threshold fallback counts corners before the
  // mask. Otherwise the pyramid is still good; FAST is not.
  const bool covers = detected_exclusion_.empty() ||
                      (!excluded_.empty() && cv::countNonZero(detected_exclusion_ > excluded_) == 0);
  for (int level = 0; level < options_.n_levels; ++level) {
    if (!covers) DetectLevel(level, exclusion_mask);
    SelectLevel(level, exclusion_mask);
  }
  if (!covers) detected_exclusion_ = excluded_.clone();
  OrbFeatures out;
  Describe(out, this);
  return out;
}

void OrbExtractor::Describe(OrbFeatures& out, const OrbExtractor* known) {
  size_t total = 0;
  for (const std::vector<FastCorner>& corners : level_corners_) total += corners.size();
  out.keypoints.clear();
  out.keypoints.reserve(total);
  out.descriptors.create(static_cast<int>(total), kDescriptorBytes, CV_8UC1);
  int row = 0;
  const auto by_key = [](const Described& a, const Described& b) { return a.key < b.key; };
  for (size_t level = 0; level < pyramid_.size(); ++level) {
    const std::vector<FastCorner>& corners = level_corners_[level];
    if (corners.empty()) continue;
    if (smoothed_[level].empty()) SmoothLevel(level);  // kept for a Reextract
    const auto scale = static_cast<float>(level_scales_[level]);
    const int width = pyramid_[level].cols;
    // Copied: `known` may be this extractor, whose list grows below.
    const std::vector<Described> earlier =
        known != nullptr && level < known->described_.size() ? known->described_[level] : std::vector<Described>();
    std::vector<Described>& described = described_[level];
    described = earlier;
    for (const FastCorner& c : corners) {
      uchar* descriptor = out.descriptors.ptr<uchar>(row++);
      const Described probe{c.y * width + c.x, 0.0f, {}};
      const auto it = std::lower_bound(earlier.begin(), earlier.end(), probe, by_key);
      float angle = 0.0f;
      if (it != earlier.end() && it->key == probe.key) {
        angle = it->angle;
        std::copy(it->descriptor.begin(), it->descriptor.end(), descriptor);
      } else {
        angle = IntensityCentroidAngle(pyramid_[level], c.x, c.y);
        brief_.Compute(smoothed_[level], c.x, c.y, angle, descriptor);
        Described& d = described.emplace_back(Described{probe.key, angle, {}});
        std::copy(descriptor, descriptor + kDescriptorBytes, d.descriptor.begin());
      }
      out.keypoints.emplace_back(cv::Point2f(static_cast<float>(c.x) * scale,
                                             static_cast<float>(c.y) * scale),
                                 static_cast<float>(kPatchSize) * scale, angle,
                                 static_cast<float>(c.score), static_cast<int>(level));
    }
    const auto added = described.begin() + static_cast<std::ptrdiff_t>(earlier.size());
    std::sort(added, described.end(), by_key);
    std::inplace_merge(described.begin(), added, described.end(), by_key);
  }
}

OrbFeatures OrbExtractor::Describe(const cv::Mat& image, const std::vector<cv::KeyPoint>& keypoints) {
  extracted_size_ = cv::Size();  // the pyramid is rebuilt without corners: no Reextract after this
  PrepareImage(image);
  for (cv::Mat& level : smoothed_) level.release();
  for (std::vector<Described>& level : described_) level.clear();
  OrbFeatures out;
  out.descriptors.create(0, kDescriptorBytes, CV_8UC1);
  cv::Mat row(1, kDescriptorBytes, CV_8UC1);
  for (const cv::KeyPoint& k : keypoints) {
    if (k.octave < 0 || k.octave >= options_.n_levels) continue;
    const auto level = static_cast<size_t>(k.octave);
    const cv::Mat& grey = pyramid_[level];
    const double scale = level_scales_[level];
    const int x = static_cast<int>(std::lround(k.pt.x / scale));
    const int y = static_cast<int>(std::lround(k.pt.y / scale));
    if (grey.empty() || x < kPatchRadius || y < kPatchRadius || x >= grey.cols - kPatchRadius ||
        y >= grey.rows - kPatchRadius) {
      continue;
    }
    if (smoothed_[level].empty()) SmoothLevel(level);
    brief_.Compute(smoothed_[level], x, y, k.angle, row.ptr<uchar>());
    out.keypoints.push_back(k);
    out.descriptors.push_back(row);
  }
  return out;
}

}  // namespace dlslam::features
