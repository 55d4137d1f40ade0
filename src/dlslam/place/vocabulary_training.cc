#include "dlslam/place/vocabulary_training.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>

#include "dlslam/place/binary_kmeans.h"
#include "dlslam/util/check.h"

namespace dlslam::place {
namespace {

int ResolveThreads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Calls job(i) for i in [0, n) on up to `threads` threads; the jobs write to
// disjoint outputs, so the result does not depend on the schedule.
void ParallelFor(std::size_t n, int threads, const std::function<void(std::size_t)>& job) {
  const int workers = static_cast<int>(std::min<std::size_t>(n, static_cast<std::size_t>(threads)));
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) job(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      try {
        job(i);
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  // A thread that cannot be started (the system's limit) leaves the work to
  // those that did; every started one is joined, never left to terminate().
  std::vector<std::thread> pool;
  try {
    for (int w = 1; w < workers; ++w) pool.emplace_back(work);
  } catch (const std::system_error&) {
  }
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

struct PendingNode {
  NodeId id = 0;
  std::vector<std::uint32_t> members;  // indices into the training descriptors
};

struct Split {
  std::vector<Descriptor> centres;  // empty: the node is a leaf
  std::vector<std::vector<std::uint32_t>> members;
};

}  // namespace

void VocabularyOptions::Check() const {
  DLSLAM_CHECK(branching >= 2 && branching <= 255, "vocabulary: k must be in [2, 255], got {}", branching);
  DLSLAM_CHECK(levels >= 1 && levels <= 16, "vocabulary: levels must be in [1, 16], got {}", levels);
  DLSLAM_CHECK(std::pow(static_cast<double>(branching), levels) < 4.0e9,
               "vocabulary: k^levels = {}^{} words do not fit 32-bit ids", branching, levels);
  DLSLAM_CHECK_GE(max_iterations, 1, "vocabulary: max_iterations must be at least 1");
  DLSLAM_CHECK(threads >= 0 && threads <= kMaxVocabularyThreads, "vocabulary: threads must be in 0..{} (0 = all), got {}",
               kMaxVocabularyThreads, threads);
}

void TrainingDescriptors::AddImage(std::span<const Descriptor> image) {
  image_starts.push_back(descriptors.size());
  descriptors.insert(descriptors.end(), image.begin(), image.end());
}

std::span<const Descriptor> TrainingDescriptors::image(std::size_t i) const {
  const std::size_t begin = image_starts[i];
  const std::size_t end = i + 1 < image_starts.size() ? image_starts[i + 1] : descriptors.size();
  return std::span<const Descriptor>(descriptors).subspan(begin, end - begin);
}

std::vector<WordWeight> ComputeIdfWeights(const Vocabulary& vocabulary, const TrainingDescriptors& training,
                                          int threads) {
  const std::size_t images = training.image_count();
  std::vector<std::vector<WordId>> words_of_image(images);
  ParallelFor(images, ResolveThreads(threads), [&](std::size_t i) {
    std::vector<WordId>& words = words_of_image[i];
    for (const Descriptor& d : training.image(i)) words.push_back(vocabulary.WordOf(d));
    std::sort(words.begin(), words.end());
    words.erase(std::unique(words.begin(), words.end()), words.end());
  });
  std::vector<std::uint32_t> images_with_word(vocabulary.word_count(), 0);
  for (const auto& words : words_of_image) {
    for (WordId w : words) ++images_with_word[w];
  }
  std::vector<WordWeight> weights(vocabulary.word_count());
  const double n = static_cast<double>(std::max<std::size_t>(images, 1));
  for (std::size_t w = 0; w < weights.size(); ++w) {
    // A word no training image reaches (its centre moved after the last
    // assignment) is treated as the rarest possible: seen once.
    const double seen = std::max<std::uint32_t>(images_with_word[w], 1);
    weights[w] = static_cast<WordWeight>(std::log(n / seen));
  }
  return weights;
}

Vocabulary TrainVocabulary(const TrainingDescriptors& training, const VocabularyOptions& options) {
  options.Check();
  DLSLAM_CHECK(!training.descriptors.empty(), "vocabulary: no training descriptors");
  DLSLAM_CHECK_LE(training.descriptors.size(), std::size_t{0xFFFFFFFFu}, "vocabulary: too many descriptors");
  const int threads = ResolveThreads(options.threads);
  const BinaryKMeansOptions kmeans{options.branching, options.max_iterations};

  std::vector<Descriptor> centres(1, Descriptor{});  // the root's centre is unused
  std::vector<std::uint8_t> child_counts(1, 0);
  std::vector<PendingNode> level(1);
  level[0].members.resize(training.descriptors.size());
  for (std::uint32_t i = 0; i < level[0].members.size(); ++i) level[0].members[i] = i;

  for (int depth = 0; depth < options.levels && !level.empty(); ++depth) {
    std::vector<Split> splits(level.size());
    ParallelFor(level.size(), threads, [&](std::size_t i) {
      const PendingNode& node = level[i];
      if (node.members.size() < 2) return;
      std::uint64_t seed_state = options.seed ^ (0x5851F42D4C957F2Dull * (node.id + 1));
      BinaryKMeansResult result = ClusterBinary(training.descriptors, node.members, kmeans, SplitMix64(seed_state));
      if (result.centres.size() < 2) return;  // all members identical: a leaf
      Split& split = splits[i];
      split.members.resize(result.centres.size());
      for (std::size_t m = 0; m < node.members.size(); ++m) {
        split.members[result.assignment[m]].push_back(node.members[m]);
      }
      split.centres = std::move(result.centres);
    });
    // Append children in the order of their parents: breadth-first ids.
    std::vector<PendingNode> next_level;
    for (std::size_t i = 0; i < level.size(); ++i) {
      Split& split = splits[i];
      child_counts[level[i].id] = static_cast<std::uint8_t>(split.centres.size());
      for (std::size_t c = 0; c < split.centres.size(); ++c) {
        next_level.push_back({static_cast<NodeId>(centres.size()), std::move(split.members[c])});
        centres.push_back(split.centres[c]);
        child_counts.push_back(0);
      }
    }
    level = std::move(next_level);
  }

  std::size_t leaves = 0;
  for (std::uint8_t c : child_counts) leaves += c == 0 ? 1 : 0;
  DLSLAM_CHECK(child_counts[0] > 0, "vocabulary: every training descriptor is the same; nothing to cluster");
  // Unit weights first: the tree is needed to find each image's words.
  Vocabulary tree(options.branching, options.levels, centres, child_counts, std::vector<WordWeight>(leaves, 1.0f));
  std::vector<WordWeight> weights = ComputeIdfWeights(tree, training, threads);
  return Vocabulary(options.branching, options.levels, std::move(centres), std::move(child_counts),
                    std::move(weights));
}

}  // namespace dlslam::place
