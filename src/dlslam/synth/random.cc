#include "dlslam/synth/random.h"

#include <array>

namespace dlslam::synth {

namespace {

std::array<float, 65536> BuildTable() {
  std::array<float, 65536> table{};
  // Newton on Phi(x) = p from the previous quantile: Phi is concave for
  // x > 0, so the iterates approach the root from below and never overshoot.
  double x = 0.0;
  for (int i = 32768; i < 65536; ++i) {
    const double p = (i + 0.5) / 65536.0;
    for (int it = 0; it < 6; ++it) {
      const double cdf = 0.5 * std::erfc(-x / std::numbers::sqrt2);
      const double pdf = std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
      x += (p - cdf) / pdf;
    }
    table[static_cast<std::size_t>(i)] = static_cast<float>(x);
    table[static_cast<std::size_t>(65535 - i)] = static_cast<float>(-x);
  }
  return table;
}

}  // namespace

const float* StandardNormalTable() {
  static const std::array<float, 65536> table = BuildTable();
  return table.data();
}

}  // namespace dlslam::synth
