#include "dlslam/place/bow_vector.h"

#include <algorithm>
#include <cmath>

namespace dlslam::place {

void SortAndMerge(BowVector& vector) {
  std::sort(vector.begin(), vector.end(),
            [](const BowEntry& a, const BowEntry& b) { return a.word < b.word; });
  std::size_t out = 0;
  for (std::size_t i = 0; i < vector.size(); ++i) {
    if (out > 0 && vector[out - 1].word == vector[i].word) {
      vector[out - 1].weight += vector[i].weight;
    } else {
      vector[out++] = vector[i];
    }
  }
  vector.resize(out);
}

void NormalizeL1(BowVector& vector) {
  double sum = 0.0;
  for (const BowEntry& entry : vector) sum += std::abs(static_cast<double>(entry.weight));
  if (sum <= 0.0) return;
  for (BowEntry& entry : vector) entry.weight = static_cast<WordWeight>(entry.weight / sum);
}

namespace {

// Calls shared(entry_a, entry_b) for every word in both sorted vectors.
template <typename Shared>
void ForEachSharedWord(const BowVector& a, const BowVector& b, Shared shared) {
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() && ib != b.end()) {
    if (ia->word < ib->word) {
      ++ia;
    } else if (ib->word < ia->word) {
      ++ib;
    } else {
      shared(*ia, *ib);
      ++ia;
      ++ib;
    }
  }
}

}  // namespace

double ScoreL1(const BowVector& a, const BowVector& b) {
  // 1 - 0.5 |a - b|_1 = 0.5 * sum over shared words of (|a_i| + |b_i| - |a_i - b_i|)
  // for vectors with |a|_1 = |b|_1 = 1 (words in only one vector cancel).
  double shared = 0.0;
  ForEachSharedWord(a, b, [&](const BowEntry& ea, const BowEntry& eb) {
    const double va = ea.weight, vb = eb.weight;
    shared += std::abs(va) + std::abs(vb) - std::abs(va - vb);
  });
  return std::clamp(0.5 * shared, 0.0, 1.0);
}

int CommonWords(const BowVector& a, const BowVector& b) {
  int common = 0;
  ForEachSharedWord(a, b, [&](const BowEntry&, const BowEntry&) { ++common; });
  return common;
}

}  // namespace dlslam::place
