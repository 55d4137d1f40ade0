#include "dlslam/match/rotation_histogram.h"

#include <algorithm>
#include <array>

namespace dlslam {
namespace {
constexpr int kRotationBins = 30;
}  // namespace

int RotationBin(float angle_a, float angle_b) {
  float d = angle_a - angle_b;
  if (d < 0) d += 360.f;
  return std::clamp(static_cast<int>(d * kRotationBins / 360.f), 0, kRotationBins - 1);
}

std::vector<bool> InDominantRotationBins(const std::vector<int>& bins) {
  std::array<int, kRotationBins> count{};
  for (int bin : bins) ++count[bin];
  std::array<int, kRotationBins> order{};
  for (int i = 0; i < kRotationBins; ++i) order[i] = i;
  std::partial_sort(order.begin(), order.begin() + 3, order.end(), [&](int a, int b) { return count[a] > count[b]; });
  std::array<bool, kRotationBins> keep{};
  for (int k = 0; k < 3; ++k) keep[order[k]] = count[order[k]] > 0 && count[order[k]] * 10 >= count[order[0]];
  std::vector<bool> out(bins.size());
  for (std::size_t i = 0; i < bins.size(); ++i) out[i] = keep[bins[i]];
  return out;
}

}  // namespace dlslam
