#include "dlslam/image/disc_dilation.h"

#include <opencv2/core/hal/intrin.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::image {

namespace {

using Word = std::uint64_t;
constexpr int kBits = 64;

// Bit x % 64 of word x / 64 is set when pixel x of the row is not 0.
void PackRow(const std::uint8_t* pixels, int cols, Word* words) {
  const int n_words = (cols + kBits - 1) / kBits;
  std::fill(words, words + n_words, Word{0});
  int x = 0;
#if CV_SIMD128
  const cv::v_uint8x16 zero = cv::v_setzero_u8();
  for (; x + 16 <= cols; x += 16) {
    const cv::v_uint8x16 set = cv::v_load(pixels + x) != zero;
    const auto bits = static_cast<Word>(static_cast<unsigned>(cv::v_signmask(cv::v_reinterpret_as_s8(set))));
    words[x / kBits] |= bits << (x % kBits);  // 16-pixel blocks never straddle a word
  }
#endif
  for (; x < cols; ++x) {
    if (pixels[x] != 0) words[x / kBits] |= Word{1} << (x % kBits);
  }
}

// Each bit of `in` set also on its two neighbours: the row grown by one
// pixel to each side (bits past the row's end are cleared when unpacked).
void GrowByOne(const Word* in, int n_words, Word* out) {
  for (int k = 0; k < n_words; ++k) {
    const Word from_left = k > 0 ? in[k - 1] >> (kBits - 1) : 0;
    const Word from_right = k + 1 < n_words ? in[k + 1] << (kBits - 1) : 0;
    out[k] = in[k] | (in[k] << 1) | from_left | (in[k] >> 1) | from_right;
  }
}

// The 8 bytes (0 or 255) for each value of 8 packed bits, lowest bit first.
const std::array<Word, 256>& ByteTable() {
  static const std::array<Word, 256> table = [] {
    std::array<Word, 256> t{};
    for (int b = 0; b < 256; ++b) {
      std::uint8_t bytes[8];
      for (int i = 0; i < 8; ++i) bytes[i] = (b >> i) & 1 ? 255 : 0;
      std::memcpy(&t[static_cast<std::size_t>(b)], bytes, 8);
    }
    return t;
  }();
  return table;
}

void UnpackRow(const Word* words, int cols, std::uint8_t* pixels) {
  const std::array<Word, 256>& table = ByteTable();
  int x = 0;
  // A mask's rows are long runs: most words are all clear or all set.
  for (; x + kBits <= cols; x += kBits) {
    const Word word = words[x / kBits];
    if (word == 0 || word == ~Word{0}) {
      std::memset(pixels + x, word == 0 ? 0 : 255, kBits);
      continue;
    }
    for (int b = 0; b < kBits; b += 8) {
      std::memcpy(pixels + x + b, &table[static_cast<std::size_t>((word >> b) & 0xFF)], 8);
    }
  }
  for (; x + 8 <= cols; x += 8) {
    const auto bits = static_cast<std::size_t>((words[x / kBits] >> (x % kBits)) & 0xFF);
    std::memcpy(pixels + x, &table[bits], 8);
  }
  for (; x < cols; ++x) pixels[x] = (words[x / kBits] >> (x % kBits)) & 1 ? 255 : 0;
}

}  // namespace

int DiscHalfWidth(int radius, int dy) {
  DLSLAM_CHECK(radius >= 0 && std::abs(dy) <= radius, "DiscHalfWidth: need |dy| {} <= radius {}", dy, radius);
  if (radius == 0) return 0;
  // OpenCV's expression for its ellipse kernel (c * sqrt((r^2 - dy^2) / r^2)
  // with c = r), rounded as it rounds, so the discs agree on every pixel.
  const double r = radius;
  return cv::saturate_cast<int>(r * std::sqrt((r * r - static_cast<double>(dy) * dy) * (1.0 / (r * r))));
}

cv::Mat DilateDisc(const cv::Mat& mask, int radius) {
  cv::Mat out;
  DilateDisc(mask, radius, out);
  return out;
}

void DilateDisc(const cv::Mat& mask, int radius, cv::Mat& out) {
  DLSLAM_CHECK(mask.type() == CV_8UC1, "DilateDisc: the mask must be CV_8UC1, got {}", cv::typeToString(mask.type()));
  DLSLAM_CHECK(radius >= 0, "DilateDisc: radius {} [px] must be >= 0", radius);
  const int rows = mask.rows;
  const int cols = mask.cols;
  if (mask.empty()) {
    out.release();
    return;
  }
  const int n_words = (cols + kBits - 1) / kBits;
  const auto plane = static_cast<std::size_t>(n_words) * static_cast<std::size_t>(rows);

  std::vector<int> half(static_cast<std::size_t>(radius) + 1);
  for (int dy = 0; dy <= radius; ++dy) half[static_cast<std::size_t>(dy)] = DiscHalfWidth(radius, dy);
  const int widest = half[0];
  // Plane w: every row grown sideways by w pixels, for w = 0 .. widest.
  // Reused by the thread: fresh pages cost more than the work.
  thread_local std::vector<Word> planes;
  planes.resize(plane * (static_cast<std::size_t>(widest) + 1));
  const auto grown = [&](int w) { return planes.data() + plane * static_cast<std::size_t>(w); };
  for (int y = 0; y < rows; ++y) {
    PackRow(mask.ptr<std::uint8_t>(y), cols, grown(0) + static_cast<std::size_t>(y) * n_words);
  }
  for (int w = 1; w <= widest; ++w) {
    for (int y = 0; y < rows; ++y) {
      const std::size_t at = static_cast<std::size_t>(y) * n_words;
      GrowByOne(grown(w - 1) + at, n_words, grown(w) + at);
    }
  }
  // The whole mask is packed: `out` may now be the mask itself.
  out.create(mask.size(), CV_8UC1);
  // Row y of the result: the OR of row y + dy grown by the disc's half-width
  // at dy, over the rows inside the image.
  std::vector<Word> row(static_cast<std::size_t>(n_words));
  for (int y = 0; y < rows; ++y) {
    std::fill(row.begin(), row.end(), Word{0});
    for (int dy = -radius; dy <= radius; ++dy) {
      const int source = y + dy;
      if (source < 0 || source >= rows) continue;
      const Word* from =
          grown(half[static_cast<std::size_t>(std::abs(dy))]) + static_cast<std::size_t>(source) * n_words;
      for (int k = 0; k < n_words; ++k) row[static_cast<std::size_t>(k)] |= from[k];
    }
    UnpackRow(row.data(), cols, out.ptr<std::uint8_t>(y));
  }
}

}  // namespace dlslam::image
