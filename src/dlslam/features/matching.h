#pragma once
// Hamming distance of 256-bit descriptors and a brute-force matcher (for
// tests and evaluation; tracking searches by projection instead).

#include <opencv2/core.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "dlslam/features/orb_options.h"

namespace dlslam::features {

namespace detail {
// The bit count, inlined into a caller built for the CPU (DLSLAM_POPCNT_CLONES).
inline int HammingDistanceInline(const uchar* a, const uchar* b) {
  int distance = 0;
  for (int word = 0; word < kDescriptorBytes / 8; ++word) {
    uint64_t wa, wb;  // memcpy: descriptors need not be 8-byte aligned
    std::memcpy(&wa, a + 8 * word, sizeof wa);
    std::memcpy(&wb, b + 8 * word, sizeof wb);
    distance += std::popcount(wa ^ wb);
  }
  return distance;
}
}  // namespace detail

// Bits that differ between two kDescriptorBytes-byte descriptors. Out of
// line, with the POPCNT instruction where the CPU has it: inlined into code
// built for baseline x86-64, std::popcount is a library call per word
// (__popcountdi2, 2 % of a full-mode run's CPU on the Bonn crowd).
int HammingDistance(const uchar* a, const uchar* b);

struct MatchOptions {
  // Keep a match only if best < ratio * second best distance (Lowe's test);
  // 1 disables it. In (0, 1].
  double ratio = 0.8;
  // Keep a match only if the train descriptor's best match is the query too.
  bool mutual = true;
  // Largest accepted distance [bits, 0..256].
  int max_distance = 256;

  void Check() const;  // throws dlslam::Error
};

// For each query row the nearest train row (cv::DMatch: queryIdx, trainIdx,
// distance in bits) that passes the tests. Both CV_8UC1 with
// kDescriptorBytes columns (or empty); throws dlslam::Error otherwise.
std::vector<cv::DMatch> MatchBruteForce(const cv::Mat& query, const cv::Mat& train,
                                        const MatchOptions& options = {});

}  // namespace dlslam::features
