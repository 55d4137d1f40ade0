#pragma once
// FAST-9 corners (16-pixel Bresenham circle of radius 3, 9 contiguous pixels
// all brighter than centre + t or all darker than centre - t), with the
// score, 3x3 non-maximum suppression, and ORB-SLAM's grid with a threshold
// fallback. Written for speed: 16 pixels at a time with OpenCV's universal
// intrinsics (32 with AVX2 where the CPU has it), scores only for corners.

#include <opencv2/core.hpp>

#include <vector>

namespace dlslam::features {

struct FastCorner {
  int x = 0;  // pixel in the detection image
  int y = 0;
  int score = 0;  // largest threshold at which the pixel is still a corner
};

// The FAST-9 score of the pixel at `p` (circle offsets for the image's row
// step, see FastCircleOffsets): the largest t such that 9 contiguous circle
// pixels are all > centre + t or all < centre - t; 0 when there is none.
int Fast9Score(const uchar* p, const int circle_offsets[16]);

// The 16 circle offsets (in elements) for an image with the given row step.
void FastCircleOffsets(int step, int offsets[16]);

// Writes into `scores` (CV_8UC1 of the image's size, allocated if needed;
// pixels outside `region` are left as they are) the FAST-9 score of every
// pixel of `region` that is a corner at `threshold`, and 0 for the others;
// appends the corners, row by row, to `candidates`. `region` must keep 3 px
// away from the image's edges.
void ComputeFastScores(const cv::Mat& image, const cv::Rect& region, int threshold,
                       cv::Mat& scores, std::vector<cv::Point>& candidates);

// Appends the candidates inside `region` whose score is >= threshold and
// strictly larger than each of their 8 neighbours' scores. `region` must keep
// 1 px away from the edges of `scores`, and the neighbours of each candidate
// must have been scored.
void SuppressNonMaxima(const cv::Mat& scores, const std::vector<cv::Point>& candidates,
                       const cv::Rect& region, int threshold, std::vector<FastCorner>& corners);

struct GridFastParams {
  int threshold_initial = 20;  // [grey levels]
  int threshold_min = 7;       // [grey levels] for cells where the initial one found nothing
  int cell_size = 30;          // [px]
};

// Memory reused between calls.
struct FastScratch {
  cv::Mat scores;
  std::vector<cv::Point> candidates;
};

// The cells of DetectGridFast: `area` cut into n equal-ish slices per axis
// (n = area side / cell_size, rounded), slice c starting at c * side / n.
struct FastGrid {
  FastGrid(const cv::Rect& area, int cell_size);
  cv::Rect Cell(int row, int col) const;
  int ColOf(int x) const;  // of a pixel inside the area
  int RowOf(int y) const;
  int Index(int row, int col) const { return row * cols + col; }  // row-major
  int size() const { return rows * cols; }
  cv::Rect area;
  int cols = 1;
  int rows = 1;
};

// FAST over `area` (4 px or more inside the image) cell by cell: corners at
// the initial threshold, and in each cell where none survived non-maximum
// suppression, corners at the minimum threshold. Appends to `corners`.
// `skip_cells`: empty, or one flag per cell of FastGrid(area,
// params.cell_size), row-major: cells whose corners the caller would drop
// anyway (wholly inside an exclusion mask) are not searched. The corners of
// the other cells are exactly those found without skipping, in the same order.
void DetectGridFast(const cv::Mat& image, const cv::Rect& area, const GridFastParams& params,
                    FastScratch& scratch, std::vector<FastCorner>& corners,
                    const std::vector<bool>& skip_cells = {});

}  // namespace dlslam::features
