#pragma once
// The 256 binary tests of the ORB descriptor. Ours are learned from real
// images as in the ORB paper (Rublee et al. 2011, section 4.3) by
// tools/learn_orb_pattern.cc; see docs/features.md.

#include <cstdint>
#include <span>
#include <vector>

namespace dlslam::features {

// One test: bit = I(x1, y1) < I(x2, y2), offsets from the keypoint [px]
// before rotation by the keypoint's angle.
struct PatternTest {
  int8_t x1, y1, x2, y2;
};

inline constexpr int kPatternTests = 256;
// Test points lie in this disc [px], so that rotated and rounded they stay
// inside the 31 x 31 patch (radius 15 matched better than the paper's 13,
// the centres of 5 x 5 sub-windows; see docs/features.md).
inline constexpr int kPatternRadius = 15;

// The learned pattern (orb_pattern_learned.h).
std::span<const PatternTest> LearnedOrbPattern();

enum class RandomPatternKind {
  kUniform,   // both points uniform in the disc of kPatternRadius
  kGaussian,  // both points isotropic Gaussian, sigma = 31 / 5 px (BRIEF's G II), clipped to the disc
};

// A random pattern of kPatternTests tests (distinct points), for comparing
// against the learned one. Deterministic for a seed.
std::vector<PatternTest> RandomOrbPattern(RandomPatternKind kind, uint32_t seed);

}  // namespace dlslam::features
