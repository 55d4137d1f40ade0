#include "dlslam/features/orb_pattern.h"

#include <cmath>
#include <random>

#include "dlslam/features/orb_pattern_learned.h"

namespace dlslam::features {

std::span<const PatternTest> LearnedOrbPattern() { return kLearnedOrbPattern; }

std::vector<PatternTest> RandomOrbPattern(RandomPatternKind kind, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-kPatternRadius, kPatternRadius);
  std::normal_distribution<double> gaussian(0.0, 31.0 / 5.0);
  const auto draw = [&](int8_t& x, int8_t& y) {
    while (true) {
      const double fx = kind == RandomPatternKind::kUniform ? uniform(rng) : gaussian(rng);
      const double fy = kind == RandomPatternKind::kUniform ? uniform(rng) : gaussian(rng);
      const long ix = std::lround(fx), iy = std::lround(fy);
      if (ix * ix + iy * iy <= kPatternRadius * kPatternRadius) {
        x = static_cast<int8_t>(ix);
        y = static_cast<int8_t>(iy);
        return;
      }
    }
  };
  std::vector<PatternTest> tests(kPatternTests);
  for (PatternTest& t : tests) {
    do {
      draw(t.x1, t.y1);
      draw(t.x2, t.y2);
    } while (t.x1 == t.x2 && t.y1 == t.y2);
  }
  return tests;
}

}  // namespace dlslam::features
