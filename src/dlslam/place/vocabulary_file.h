#pragma once
// The binary vocabulary file (.dlv), little-endian:
//
//   offset  size  field
//        0     8  magic "DLSVOCAB"
//        8     4  version (1)
//       12     4  k (branching factor)
//       16     4  levels below the root
//       20     4  node count n (root included)
//       24     4  word count w
//       28     4  weighting (1 = tf-idf) | scoring (1 = L1) << 16
//       32     8  payload bytes (= 32 n + n + padding to 4 + 4 w)
//       40     8  training images
//       48     8  training descriptors
//       56     8  reserved (0)
//       64  32 n  node centres, breadth-first (the root's is zeros)
//           n     child count per node; zero bytes up to a multiple of 4
//           4 w   idf weight per word, float32
//  end - 4     4  CRC-32 (zlib's) of every byte before it
//
// A file is read with one read into memory; every defect (missing, wrong
// magic, other version, truncated, checksum, counts that disagree, a tree
// that is not one) is an InputError naming the file and, where it helps,
// the byte offset.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "dlslam/place/vocabulary.h"

namespace dlslam::place {

inline constexpr std::uint32_t kVocabularyFileVersion = 1;
// The vocabulary we ship in models/ (models/README.md).
inline constexpr std::string_view kShippedVocabularyName = "orb_vocab_k10_l5.dlv";

struct TrainingSummary {
  std::uint64_t images = 0;
  std::uint64_t descriptors = 0;
};

// The file's bytes. Throws dlslam::Error for an empty vocabulary.
std::string SerializeVocabulary(const Vocabulary& vocabulary, const TrainingSummary& summary = {});
// Parses bytes read from `file` (named in errors). Throws InputError.
Vocabulary ParseVocabulary(std::string_view bytes, const std::filesystem::path& file,
                           TrainingSummary* summary = nullptr);

// Writes atomically (a failed write leaves an existing file untouched).
void SaveVocabulary(const Vocabulary& vocabulary, const std::filesystem::path& file,
                    const TrainingSummary& summary = {});
Vocabulary LoadVocabulary(const std::filesystem::path& file, TrainingSummary* summary = nullptr);

// The vocabulary file to use: `explicit_path` when given, else the shipped
// one found like every model (io/model_file.h). Throws InputError.
std::filesystem::path FindVocabulary(const std::filesystem::path& explicit_path = {});

}  // namespace dlslam::place
