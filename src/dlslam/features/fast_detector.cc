#include "dlslam/features/fast_detector.h"

#include <opencv2/core/hal/intrin.hpp>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define DLSLAM_FAST_AVX2 1
#endif

#include <algorithm>
#include <bit>
#include <cstdint>

#include "dlslam/util/check.h"

namespace dlslam::features {
namespace {

// Circle of radius 3 clockwise from the top (x right, y down).
constexpr int kCircleX[16] = {0, 1, 2, 3, 3, 3, 2, 1, 0, -1, -2, -3, -3, -3, -2, -1};
constexpr int kCircleY[16] = {-3, -3, -2, -1, 0, 1, 2, 3, 3, 3, 2, 1, 0, -1, -2, -3};
constexpr int kArc = 9;

void CheckRegion(const cv::Mat& image, const cv::Rect& region, int margin, const char* what) {
  DLSLAM_CHECK(region.x >= margin && region.y >= margin &&
                   region.x + region.width <= image.cols - margin &&
                   region.y + region.height <= image.rows - margin,
               "{}: region ({}, {}, {}x{}) not {} px inside the {}x{} image", what, region.x,
               region.y, region.width, region.height, margin, image.cols, image.rows);
}

#if CV_SIMD128
// Pixel v as a signed byte with the unsigned order (top bit flipped).
inline cv::v_int8x16 AsSigned(const cv::v_uint8x16& v) {
  return cv::v_reinterpret_as_s8(v ^ cv::v_setall_u8(0x80));
}

// Scores of the 16 pixels p .. p + 15 at once, as Fast9Score computes them:
// with saturating differences (brighter: circle - centre, darker: centre -
// circle, 0 when the other way round) the best arc's minimum, by windows of
// 2, 4, 8 and 9 pixels built by doubling.
inline cv::v_uint8x16 BlockScores(const uchar* p, const int offsets[16]) {
  const cv::v_uint8x16 centre = cv::v_load(p);
  cv::v_uint8x16 bright[16], dark[16];
  for (int k = 0; k < 16; ++k) {
    const cv::v_uint8x16 c = cv::v_load(p + offsets[k]);
    bright[k] = c - centre;  // saturating
    dark[k] = centre - c;
  }
  const auto best_arc = [](const cv::v_uint8x16 (&diff)[16]) {
    cv::v_uint8x16 w2[16], w4[16];
    for (int k = 0; k < 16; ++k) w2[k] = cv::v_min(diff[k], diff[(k + 1) & 15]);
    for (int k = 0; k < 16; ++k) w4[k] = cv::v_min(w2[k], w2[(k + 2) & 15]);
    cv::v_uint8x16 best = cv::v_setzero_u8();
    for (int k = 0; k < 16; ++k) {
      const cv::v_uint8x16 w8 = cv::v_min(w4[k], w4[(k + 4) & 15]);
      best = cv::v_max(best, cv::v_min(w8, diff[(k + 8) & 15]));
    }
    return best;
  };
  // Corner at t <=> best arc minimum > t, so the score is that minimum - 1.
  return cv::v_max(best_arc(bright), best_arc(dark)) - cv::v_setall_u8(1);
}
#endif

#if DLSLAM_FAST_AVX2
// AVX2 code, chosen at run time (the build targets baseline x86-64). Helpers
// carry the target themselves: lambdas would not inherit it.
#define DLSLAM_AVX2 __attribute__((target("avx2"), always_inline)) inline

DLSLAM_AVX2 __m256i Load32(const uchar* q) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q)); }

// The best arc's minimum of 32 pixels' differences, as in BlockScores.
DLSLAM_AVX2 __m256i BestArc32(const __m256i (&diff)[16]) {
  __m256i w2[16], w4[16];
  for (int k = 0; k < 16; ++k) w2[k] = _mm256_min_epu8(diff[k], diff[(k + 1) & 15]);
  for (int k = 0; k < 16; ++k) w4[k] = _mm256_min_epu8(w2[k], w2[(k + 2) & 15]);
  __m256i best = _mm256_setzero_si256();
  for (int k = 0; k < 16; ++k) {
    const __m256i w8 = _mm256_min_epu8(w4[k], w4[(k + 4) & 15]);
    best = _mm256_max_epu8(best, _mm256_min_epu8(w8, diff[(k + 8) & 15]));
  }
  return best;
}

// One row of ComputeFastScores 32 pixels at a time: the same arithmetic as
// the 16-lane path, so the same scores to the bit. Needs x_end - x >= 32.
__attribute__((target("avx2"))) void ScoreRowAvx2(const uchar* row, const int offsets[16], int x, int x_end, int y,
                                                  int threshold, uchar* score_row,
                                                  std::vector<cv::Point>& candidates) {
  constexpr int kLanes = 32;
  const __m256i flip = _mm256_set1_epi8(static_cast<char>(0x80));  // unsigned order as signed bytes
  const __m256i t = _mm256_set1_epi8(static_cast<char>(threshold));
  const __m256i one = _mm256_set1_epi8(1);
  int done_until = x;
  for (; x < x_end; x += kLanes) {
    x = std::min(x, x_end - kLanes);
    const uchar* p = row + x;
    const __m256i centre = Load32(p);
    const __m256i brighter_than = _mm256_xor_si256(_mm256_adds_epu8(centre, t), flip);
    const __m256i darker_than = _mm256_xor_si256(_mm256_subs_epu8(centre, t), flip);
    __m256i bright[4], dark[4];  // circle pixels 0, 4, 8, 12: every arc of 9 holds one of 0/8 and one of 4/12
    for (int i = 0; i < 4; ++i) {
      const __m256i c = _mm256_xor_si256(Load32(p + offsets[4 * i]), flip);
      bright[i] = _mm256_cmpgt_epi8(c, brighter_than);
      dark[i] = _mm256_cmpgt_epi8(darker_than, c);
    }
    const __m256i maybe = _mm256_or_si256(
        _mm256_and_si256(_mm256_or_si256(bright[0], bright[2]), _mm256_or_si256(bright[1], bright[3])),
        _mm256_and_si256(_mm256_or_si256(dark[0], dark[2]), _mm256_or_si256(dark[1], dark[3])));
    if (_mm256_testz_si256(maybe, maybe)) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(score_row + x), _mm256_setzero_si256());
      done_until = x + kLanes;
      continue;
    }
    __m256i up[16], down[16];  // saturating differences circle - centre, centre - circle
    for (int k = 0; k < 16; ++k) {
      const __m256i c = Load32(p + offsets[k]);
      up[k] = _mm256_subs_epu8(c, centre);
      down[k] = _mm256_subs_epu8(centre, c);
    }
    const __m256i scores = _mm256_subs_epu8(_mm256_max_epu8(BestArc32(up), BestArc32(down)), one);
    const __m256i is_corner = _mm256_cmpeq_epi8(_mm256_max_epu8(scores, t), scores);  // scores >= t
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(score_row + x), _mm256_and_si256(scores, is_corner));
    auto lanes = static_cast<std::uint32_t>(_mm256_movemask_epi8(is_corner));
    if (x < done_until) lanes &= ~0u << (done_until - x);  // listed by the previous block
    for (; lanes != 0; lanes &= lanes - 1) candidates.emplace_back(x + std::countr_zero(lanes), y);
    done_until = x + kLanes;
  }
}
#undef DLSLAM_AVX2

bool CpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

}  // namespace

void FastCircleOffsets(int step, int offsets[16]) {
  for (int k = 0; k < 16; ++k) offsets[k] = kCircleY[k] * step + kCircleX[k];
}

int Fast9Score(const uchar* p, const int circle_offsets[16]) {
  // d[k] = circle pixel k minus the centre. The score is the best over the
  // 16 arcs of 9 of the arc's smallest difference (bright) or of minus its
  // largest one (dark); windows of 9 are built by doubling (2, 4, 8, +1).
  alignas(16) int16_t d[16];
  const int centre = p[0];
  for (int k = 0; k < 16; ++k) d[k] = static_cast<int16_t>(p[circle_offsets[k]] - centre);
  int best_bright = 0, best_dark = 0;  // max of arc minima, min of arc maxima
#if CV_SIMD128
  // Arcs starting at 0..7 (first vector) and 8..15 (second); the circle
  // wraps, so element k + n of the first is element k + n - 8 of the second.
  const cv::v_int16x8 a = cv::v_load_aligned(d), b = cv::v_load_aligned(d + 8);
  cv::v_int16x8 lo_a = cv::v_min(a, cv::v_extract<1>(a, b));
  cv::v_int16x8 lo_b = cv::v_min(b, cv::v_extract<1>(b, a));
  cv::v_int16x8 hi_a = cv::v_max(a, cv::v_extract<1>(a, b));
  cv::v_int16x8 hi_b = cv::v_max(b, cv::v_extract<1>(b, a));
  cv::v_int16x8 t_a = cv::v_min(lo_a, cv::v_extract<2>(lo_a, lo_b));
  lo_b = cv::v_min(lo_b, cv::v_extract<2>(lo_b, lo_a));
  lo_a = t_a;
  t_a = cv::v_max(hi_a, cv::v_extract<2>(hi_a, hi_b));
  hi_b = cv::v_max(hi_b, cv::v_extract<2>(hi_b, hi_a));
  hi_a = t_a;
  t_a = cv::v_min(lo_a, cv::v_extract<4>(lo_a, lo_b));
  lo_b = cv::v_min(lo_b, cv::v_extract<4>(lo_b, lo_a));
  lo_a = t_a;
  t_a = cv::v_max(hi_a, cv::v_extract<4>(hi_a, hi_b));
  hi_b = cv::v_max(hi_b, cv::v_extract<4>(hi_b, hi_a));
  hi_a = t_a;
  // Ninth element: d[k + 8] is b for arcs 0..7 and a for arcs 8..15.
  best_bright = cv::v_reduce_max(cv::v_max(cv::v_min(lo_a, b), cv::v_min(lo_b, a)));
  best_dark = cv::v_reduce_min(cv::v_min(cv::v_max(hi_a, b), cv::v_max(hi_b, a)));
#else
  best_bright = -256;
  best_dark = 256;
  for (int k = 0; k < 16; ++k) {
    int arc_min = 256, arc_max = -256;
    for (int j = 0; j < kArc; ++j) {
      arc_min = std::min<int>(arc_min, d[(k + j) & 15]);
      arc_max = std::max<int>(arc_max, d[(k + j) & 15]);
    }
    best_bright = std::max(best_bright, arc_min);
    best_dark = std::min(best_dark, arc_max);
  }
#endif
  // Corner at t <=> some arc has all differences > t (bright) or < -t (dark).
  return std::max({best_bright - 1, -best_dark - 1, 0});
}

void ComputeFastScores(const cv::Mat& image, const cv::Rect& region, int threshold,
                       cv::Mat& scores, std::vector<cv::Point>& candidates) {
  DLSLAM_CHECK_EQ(image.type(), CV_8UC1, "FAST needs an 8-bit grey image");
  DLSLAM_CHECK(threshold >= 1 && threshold <= 254, "FAST threshold {}", threshold);
  CheckRegion(image, region, 3, "ComputeFastScores");
  scores.create(image.size(), CV_8UC1);
  int offsets[16];
  FastCircleOffsets(static_cast<int>(image.step1()), offsets);
  const int x_end = region.x + region.width;
  constexpr int kLanes = 16;
#if DLSLAM_FAST_AVX2
  const bool avx2_rows = region.width >= 32 && CpuHasAvx2();
#endif

  for (int y = region.y; y < region.y + region.height; ++y) {
    const uchar* row = image.ptr<uchar>(y);
    uchar* score_row = scores.ptr<uchar>(y);
    int x = region.x;
#if DLSLAM_FAST_AVX2
    if (avx2_rows) {
      ScoreRowAvx2(row, offsets, x, x_end, y, threshold, score_row, candidates);
      continue;
    }
#endif
#if CV_SIMD128
    int done_until = x;  // pixels before it are scored already
    const cv::v_uint8x16 t = cv::v_setall_u8(static_cast<uchar>(threshold));
    const cv::v_uint8x16 below_threshold = cv::v_setall_u8(static_cast<uchar>(threshold - 1));
    for (; region.width >= kLanes && x < x_end; x += kLanes) {
      x = std::min(x, x_end - kLanes);  // the last block may overlap the previous one
      const uchar* p = row + x;
      const cv::v_uint8x16 centre = cv::v_load(p);
      const cv::v_int8x16 brighter_than = AsSigned(centre + t);  // saturating
      const cv::v_int8x16 darker_than = AsSigned(centre - t);
      // Every arc of 9 holds one of pixels 0/8 and one of pixels 4/12.
      const cv::v_int8x16 c0 = AsSigned(cv::v_load(p + offsets[0]));
      const cv::v_int8x16 c4 = AsSigned(cv::v_load(p + offsets[4]));
      const cv::v_int8x16 c8 = AsSigned(cv::v_load(p + offsets[8]));
      const cv::v_int8x16 c12 = AsSigned(cv::v_load(p + offsets[12]));
      const cv::v_int8x16 maybe_bright = ((c0 > brighter_than) | (c8 > brighter_than)) &
                                         ((c4 > brighter_than) | (c12 > brighter_than));
      const cv::v_int8x16 maybe_dark = ((c0 < darker_than) | (c8 < darker_than)) &
                                       ((c4 < darker_than) | (c12 < darker_than));
      if (!cv::v_check_any(maybe_bright | maybe_dark)) {
        cv::v_store(score_row + x, cv::v_setzero_u8());
        done_until = x + kLanes;
        continue;
      }
      const cv::v_uint8x16 block_scores = BlockScores(p, offsets);
      const cv::v_uint8x16 is_corner = block_scores > below_threshold;
      cv::v_store(score_row + x, block_scores & is_corner);
      unsigned lanes = static_cast<unsigned>(cv::v_signmask(is_corner));
      // Pixels an overlapping last block shares with the previous one are listed already.
      if (x < done_until) lanes &= ~0u << (done_until - x);
      for (; lanes != 0; lanes &= lanes - 1) candidates.emplace_back(x + std::countr_zero(lanes), y);
      done_until = x + kLanes;
    }
#endif
    for (; x < x_end; ++x) {  // narrow regions, or no SIMD
      const int score = Fast9Score(row + x, offsets);
      const bool corner = score >= threshold;
      score_row[x] = static_cast<uchar>(corner ? score : 0);
      if (corner) candidates.emplace_back(x, y);
    }
  }
}

void SuppressNonMaxima(const cv::Mat& scores, const std::vector<cv::Point>& candidates,
                       const cv::Rect& region, int threshold, std::vector<FastCorner>& corners) {
  DLSLAM_CHECK_EQ(scores.type(), CV_8UC1, "FAST scores");
  CheckRegion(scores, region, 1, "SuppressNonMaxima");
  const int step = static_cast<int>(scores.step1());
  for (const cv::Point& p : candidates) {
    if (!region.contains(p)) continue;
    const uchar* c = scores.ptr<uchar>(p.y) + p.x;
    const int s = c[0];
    if (s >= threshold && s > c[-1] && s > c[1] && s > c[-step - 1] && s > c[-step] &&
        s > c[-step + 1] && s > c[step - 1] && s > c[step] && s > c[step + 1]) {
      corners.push_back({p.x, p.y, s});
    }
  }
}

FastGrid::FastGrid(const cv::Rect& area_in, int cell_size)
    : area(area_in),
      cols(std::max(1, (area_in.width + cell_size / 2) / cell_size)),
      rows(std::max(1, (area_in.height + cell_size / 2) / cell_size)) {}

cv::Rect FastGrid::Cell(int row, int col) const {
  const int x0 = area.x + col * area.width / cols;
  const int x1 = area.x + (col + 1) * area.width / cols;
  const int y0 = area.y + row * area.height / rows;
  const int y1 = area.y + (row + 1) * area.height / rows;
  return {x0, y0, x1 - x0, y1 - y0};
}

namespace {

// The largest c with c * size / n <= offset (integer division as in Cell).
int SliceOf(int offset, int size, int n) { return ((offset + 1) * n + size - 1) / size - 1; }

}  // namespace

int FastGrid::ColOf(int x) const { return SliceOf(x - area.x, area.width, cols); }
int FastGrid::RowOf(int y) const { return SliceOf(y - area.y, area.height, rows); }

void DetectGridFast(const cv::Mat& image, const cv::Rect& area, const GridFastParams& params,
                    FastScratch& scratch, std::vector<FastCorner>& corners, const std::vector<bool>& skip_cells) {
  DLSLAM_CHECK(params.threshold_min >= 1 && params.threshold_min <= params.threshold_initial,
               "FAST thresholds min {} initial {}", params.threshold_min,
               params.threshold_initial);
  DLSLAM_CHECK_GT(params.cell_size, 0, "FAST cell size");
  if (area.width <= 0 || area.height <= 0) return;
  CheckRegion(image, area, 4, "DetectGridFast");
  const FastGrid grid(area, params.cell_size);
  const auto n_cells = static_cast<size_t>(grid.size());
  DLSLAM_CHECK(skip_cells.empty() || skip_cells.size() == n_cells, "DetectGridFast: {} cell flags for {} cells",
               skip_cells.size(), n_cells);
  const bool skipping = std::find(skip_cells.begin(), skip_cells.end(), true) != skip_cells.end();
  const auto skipped = [&](int row, int col) {
    return skipping && skip_cells[static_cast<size_t>(grid.Index(row, col))];
  };
  // Scored one pixel beyond the area so that suppression at its edge is exact.
  const cv::Rect scored_area(area.x - 1, area.y - 1, area.width + 2, area.height + 2);

  const size_t first = corners.size();
  if (!skipping) {
    scratch.candidates.clear();
    ComputeFastScores(image, scored_area, params.threshold_initial, scratch.scores, scratch.candidates);
    SuppressNonMaxima(scratch.scores, scratch.candidates, area, params.threshold_initial, corners);
  } else {
    // Each run of searched cells along a row of cells, scored one pixel
    // around; sorted back into the whole area's row-by-row order after.
    for (int row = 0; row < grid.rows; ++row) {
      for (int col = 0; col < grid.cols;) {
        if (skipped(row, col)) {
          ++col;
          continue;
        }
        int end = col;
        while (end < grid.cols && !skipped(row, end)) ++end;
        const cv::Rect run = grid.Cell(row, col) | grid.Cell(row, end - 1);
        scratch.candidates.clear();
        ComputeFastScores(image, cv::Rect(run.x - 1, run.y - 1, run.width + 2, run.height + 2) & scored_area,
                          params.threshold_initial, scratch.scores, scratch.candidates);
        SuppressNonMaxima(scratch.scores, scratch.candidates, run, params.threshold_initial, corners);
        col = end;
      }
    }
    std::sort(corners.begin() + static_cast<std::ptrdiff_t>(first), corners.end(),
              [](const FastCorner& a, const FastCorner& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
  }
  if (params.threshold_min == params.threshold_initial) return;

  std::vector<int> cell_counts(n_cells, 0);
  for (size_t i = first; i < corners.size(); ++i) {
    ++cell_counts[static_cast<size_t>(grid.Index(grid.RowOf(corners[i].y), grid.ColOf(corners[i].x)))];
  }
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      if (cell_counts[static_cast<size_t>(grid.Index(row, col))] > 0 || skipped(row, col)) continue;
      const cv::Rect cell = grid.Cell(row, col);
      // Rescored one pixel around the cell too, for exact suppression.
      const cv::Rect ring = cv::Rect(cell.x - 1, cell.y - 1, cell.width + 2, cell.height + 2) & scored_area;
      scratch.candidates.clear();
      ComputeFastScores(image, ring, params.threshold_min, scratch.scores, scratch.candidates);
      SuppressNonMaxima(scratch.scores, scratch.candidates, cell, params.threshold_min, corners);
    }
  }
}

}  // namespace dlslam::features
