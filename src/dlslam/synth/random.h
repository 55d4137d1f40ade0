#pragma once
// Seeded randomness for the synthetic sequences. Everything derives from
// std::mt19937 engines seeded through std::seed_seq (both fully specified by
// the standard) and the distributions below are our own (the standard's are
// implementation-defined). No global state. A seed gives byte-identical
// output from one build; another compiler may evaluate two draws within one
// function call's arguments in the other order and so draw another room.

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace dlslam::synth {

// An engine for one purpose: `stream` names the purpose (scene, frame
// noise, ...), `index` e.g. the frame number.
inline std::mt19937 MakeRng(std::uint32_t seed, std::uint32_t stream, std::uint32_t index = 0) {
  std::seed_seq seq{seed, stream, index, 0x5EEDu};
  return std::mt19937(seq);
}

// Uniform in the open interval (0, 1).
inline double Uniform01(std::mt19937& rng) { return (rng() + 0.5) * (1.0 / 4294967296.0); }
inline double Uniform(std::mt19937& rng, double lo, double hi) { return lo + (hi - lo) * Uniform01(rng); }
// Uniform integer in [lo, hi].
inline int UniformInt(std::mt19937& rng, int lo, int hi) {
  return lo + static_cast<int>(Uniform01(rng) * (hi - lo + 1));
}
// Log-uniform in [lo, hi]: shapes of every scale, as in real rooms.
inline double LogUniform(std::mt19937& rng, double lo, double hi) {
  return lo * std::pow(hi / lo, Uniform01(rng));
}
// Standard normal (Box-Muller).
inline double Gaussian(std::mt19937& rng) {
  const double r = std::sqrt(-2.0 * std::log(Uniform01(rng)));
  return r * std::cos(2.0 * std::numbers::pi * Uniform01(rng));
}

// Standard-normal quantiles at (i + 0.5) / 65536: a table lookup with 16
// random bits is a fast normal sample (tails cut at 4.3 sigma; the variance
// is 0.9997), used for per-pixel sensor noise.
const float* StandardNormalTable();

}  // namespace dlslam::synth
