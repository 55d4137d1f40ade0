#include "dlslam/place/vocabulary_file.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <ostream>

#include "dlslam/io/file_util.h"
#include "dlslam/io/model_file.h"
#include "dlslam/util/check.h"
#include "dlslam/util/crc32.h"

namespace dlslam::place {
namespace {

static_assert(std::endian::native == std::endian::little, "the vocabulary reader assumes a little-endian host");

constexpr char kMagic[8] = {'D', 'L', 'S', 'V', 'O', 'C', 'A', 'B'};
constexpr std::size_t kHeaderBytes = 64;
constexpr std::uint32_t kTfIdf = 1;
constexpr std::uint32_t kScoreL1 = 1;

std::uint64_t PayloadBytes(std::uint64_t nodes, std::uint64_t words) {
  const std::uint64_t counts_end = 32 * nodes + nodes;
  return (counts_end + 3) / 4 * 4 + 4 * words;
}

template <typename T>
void Put(std::string& out, std::size_t offset, T value) {
  std::memcpy(out.data() + offset, &value, sizeof value);
}

template <typename T>
T Get(std::string_view bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

}  // namespace

std::string SerializeVocabulary(const Vocabulary& vocabulary, const TrainingSummary& summary) {
  DLSLAM_CHECK(!vocabulary.empty(), "cannot write an empty vocabulary");
  const std::uint64_t nodes = vocabulary.node_count();
  const std::uint64_t words = vocabulary.word_count();
  const std::uint64_t payload = PayloadBytes(nodes, words);
  std::string out(kHeaderBytes + payload + 4, '\0');
  std::memcpy(out.data(), kMagic, sizeof kMagic);
  Put<std::uint32_t>(out, 8, kVocabularyFileVersion);
  Put<std::uint32_t>(out, 12, static_cast<std::uint32_t>(vocabulary.branching()));
  Put<std::uint32_t>(out, 16, static_cast<std::uint32_t>(vocabulary.levels()));
  Put<std::uint32_t>(out, 20, static_cast<std::uint32_t>(nodes));
  Put<std::uint32_t>(out, 24, static_cast<std::uint32_t>(words));
  Put<std::uint32_t>(out, 28, kTfIdf | kScoreL1 << 16);
  Put<std::uint64_t>(out, 32, payload);
  Put<std::uint64_t>(out, 40, summary.images);
  Put<std::uint64_t>(out, 48, summary.descriptors);
  std::size_t offset = kHeaderBytes;
  std::memcpy(out.data() + offset, vocabulary.centres().data(), 32 * nodes);
  offset += 32 * nodes;
  std::memcpy(out.data() + offset, vocabulary.child_counts().data(), nodes);
  offset = (offset + nodes + 3) / 4 * 4;
  std::memcpy(out.data() + offset, vocabulary.word_weights().data(), 4 * words);
  const std::uint32_t crc = Crc32(std::string_view(out.data(), out.size() - 4));
  Put<std::uint32_t>(out, out.size() - 4, crc);
  return out;
}

Vocabulary ParseVocabulary(std::string_view bytes, const std::filesystem::path& file, TrainingSummary* summary) {
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    throw InputError(file, 0, "not a DLSLAM vocabulary (offset 0: magic \"DLSVOCAB\" expected{})",
                     bytes.size() < 8 ? fmt::format(", file has {} bytes", bytes.size()) : "");
  }
  if (bytes.size() < kHeaderBytes + 4) {
    throw InputError(file, 0, "truncated: {} bytes, the header alone needs {}", bytes.size(), kHeaderBytes + 4);
  }
  const auto version = Get<std::uint32_t>(bytes, 8);
  if (version != kVocabularyFileVersion) {
    throw InputError(file, 0, "unsupported vocabulary version {} (offset 8); this build reads version {}",
                     version, kVocabularyFileVersion);
  }
  const auto k = Get<std::uint32_t>(bytes, 12);
  const auto levels = Get<std::uint32_t>(bytes, 16);
  const auto nodes = Get<std::uint32_t>(bytes, 20);
  const auto words = Get<std::uint32_t>(bytes, 24);
  const auto kinds = Get<std::uint32_t>(bytes, 28);
  const auto payload = Get<std::uint64_t>(bytes, 32);
  const std::uint64_t expected_size = kHeaderBytes + payload + 4;
  if (bytes.size() < expected_size) {
    throw InputError(file, 0, "truncated: {} bytes, the header (offset 32) announces {}", bytes.size(),
                     expected_size);
  }
  if (bytes.size() > expected_size) {
    throw InputError(file, 0, "{} bytes after the checksum at offset {}", bytes.size() - expected_size,
                     expected_size - 4);
  }
  const auto stored_crc = Get<std::uint32_t>(bytes, bytes.size() - 4);
  const std::uint32_t crc = Crc32(bytes.substr(0, bytes.size() - 4));
  if (crc != stored_crc) {
    throw InputError(file, 0, "checksum mismatch (stored {:08x} at offset {}, computed {:08x}): the file is corrupt",
                     stored_crc, bytes.size() - 4, crc);
  }
  if (payload != PayloadBytes(nodes, words)) {
    throw InputError(file, 0, "inconsistent counts: {} nodes and {} words need {} payload bytes, header says {}",
                     nodes, words, PayloadBytes(nodes, words), payload);
  }
  if (kinds != (kTfIdf | kScoreL1 << 16)) {
    throw InputError(file, 0, "unsupported weighting/scoring {:#x} at offset 28 (tf-idf with L1 expected)", kinds);
  }
  if (k < 2 || k > 255 || levels < 1 || levels > 16) {
    throw InputError(file, 0, "k = {} (offset 12) and levels = {} (offset 16) must be in [2, 255] and [1, 16]", k,
                     levels);
  }
  if (nodes < 2 || words >= nodes) {
    throw InputError(file, 0, "inconsistent counts: {} nodes, {} words", nodes, words);
  }
  std::vector<Descriptor> centres(nodes);
  std::size_t offset = kHeaderBytes;
  std::memcpy(centres.data(), bytes.data() + offset, 32ull * nodes);
  offset += 32ull * nodes;
  std::vector<std::uint8_t> child_counts(nodes);
  std::memcpy(child_counts.data(), bytes.data() + offset, nodes);
  offset = (offset + nodes + 3) / 4 * 4;
  std::vector<WordWeight> weights(words);
  std::memcpy(weights.data(), bytes.data() + offset, 4ull * words);
  for (std::uint32_t w = 0; w < words; ++w) {
    if (!std::isfinite(weights[w]) || weights[w] < 0) {
      throw InputError(file, 0, "word {} has weight {} (offset {}); idf weights are finite and >= 0", w,
                       weights[w], offset + 4ull * w);
    }
  }
  if (summary != nullptr) *summary = {Get<std::uint64_t>(bytes, 40), Get<std::uint64_t>(bytes, 48)};
  try {
    return Vocabulary(static_cast<int>(k), static_cast<int>(levels), std::move(centres), std::move(child_counts),
                      std::move(weights));
  } catch (const Error& e) {
    throw InputError(file, 0, "inconsistent tree: {}", e.what());
  }
}

void SaveVocabulary(const Vocabulary& vocabulary, const std::filesystem::path& file,
                    const TrainingSummary& summary) {
  const std::string bytes = SerializeVocabulary(vocabulary, summary);
  io::WriteFileAtomically(file, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

Vocabulary LoadVocabulary(const std::filesystem::path& file, TrainingSummary* summary) {
  return ParseVocabulary(io::ReadFileBytes(file), file, summary);
}

std::filesystem::path FindVocabulary(const std::filesystem::path& explicit_path) {
  return io::FindModelFile(kShippedVocabularyName, explicit_path);
}

}  // namespace dlslam::place
