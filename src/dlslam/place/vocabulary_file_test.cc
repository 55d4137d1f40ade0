#include "dlslam/place/vocabulary_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>

#include "dlslam/place/test_descriptors.h"
#include "dlslam/place/vocabulary_training.h"
#include "dlslam/util/check.h"
#include "dlslam/util/crc32.h"
#include "tests/support/test_data.h"

namespace dlslam::place {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

Vocabulary SmallVocabulary() {
  std::mt19937 rng(21);
  std::vector<Descriptor> data;
  for (int i = 0; i < 400; ++i) data.push_back(testing::RandomDescriptor(rng));
  VocabularyOptions options;
  options.branching = 3;
  options.levels = 3;
  return TrainVocabulary(testing::SplitIntoImages(data, 8), options);
}

class VocabularyFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = dlslam::testing::MakeTempDir("vocabulary_file");
    bytes_ = SerializeVocabulary(vocabulary_, {8, 400});
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path Write(const std::string& name, const std::string& bytes) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
  }
  // Error message of loading `bytes` from a file; "" when it loads.
  std::string LoadError(const std::string& bytes) {
    const auto path = Write("bad.dlv", bytes);
    try {
      LoadVocabulary(path);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      return e.what();
    }
    return "";
  }
  // Rewrites the trailing checksum so only the intended defect remains.
  static std::string Resealed(std::string bytes) {
    const std::uint32_t crc = Crc32(std::string_view(bytes.data(), bytes.size() - 4));
    std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);
    return bytes;
  }
  template <typename T>
  static std::string With(std::string bytes, std::size_t offset, T value) {
    std::memcpy(bytes.data() + offset, &value, sizeof value);
    return bytes;
  }

  Vocabulary vocabulary_ = SmallVocabulary();
  std::filesystem::path dir_;
  std::string bytes_;
};

TEST_F(VocabularyFileTest, RoundTripKeepsEveryPart) {
  const auto path = dir_ / "v.dlv";
  SaveVocabulary(vocabulary_, path, {8, 400});
  TrainingSummary summary;
  const Vocabulary loaded = LoadVocabulary(path, &summary);
  EXPECT_EQ(loaded.branching(), 3);
  EXPECT_EQ(loaded.levels(), 3);
  EXPECT_EQ(loaded.centres(), vocabulary_.centres());
  EXPECT_EQ(loaded.child_counts(), vocabulary_.child_counts());
  EXPECT_EQ(loaded.word_weights(), vocabulary_.word_weights());
  EXPECT_EQ(summary.images, 8u);
  EXPECT_EQ(summary.descriptors, 400u);
  EXPECT_EQ(std::filesystem::file_size(path), bytes_.size());
  // Layout as documented: 64-byte header, 33 bytes per node padded to 4,
  // 4 per word, 4 of checksum.
  const std::size_t n = vocabulary_.node_count(), w = vocabulary_.word_count();
  EXPECT_EQ(bytes_.size(), 64 + (33 * n + 3) / 4 * 4 + 4 * w + 4);
  EXPECT_EQ(bytes_.substr(0, 8), "DLSVOCAB");
}

TEST_F(VocabularyFileTest, MissingFile) {
  try {
    LoadVocabulary(dir_ / "none.dlv");
    FAIL() << "loaded a missing file";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("none.dlv"), HasSubstr("not found")));
  }
}

TEST_F(VocabularyFileTest, WrongMagic) {
  std::string bytes = bytes_;
  bytes[0] = 'X';
  EXPECT_THAT(LoadError(bytes), AllOf(HasSubstr("bad.dlv"), HasSubstr("not a DLSLAM vocabulary")));
  EXPECT_THAT(LoadError("# a DBoW2 text vocabulary\n10 6 0 0\n"), HasSubstr("not a DLSLAM vocabulary"));
  EXPECT_THAT(LoadError(""), HasSubstr("not a DLSLAM vocabulary"));
}

TEST_F(VocabularyFileTest, UnsupportedVersion) {
  EXPECT_THAT(LoadError(Resealed(With<std::uint32_t>(bytes_, 8, 2))),
              AllOf(HasSubstr("unsupported vocabulary version 2"), HasSubstr("offset 8")));
}

TEST_F(VocabularyFileTest, TruncatedAnywhere) {
  for (std::size_t length : {std::size_t{8}, std::size_t{40}, std::size_t{67}, bytes_.size() / 2, bytes_.size() - 1}) {
    EXPECT_THAT(LoadError(bytes_.substr(0, length)), HasSubstr("truncated")) << length << " bytes";
  }
  EXPECT_THAT(LoadError(bytes_ + "extra"), HasSubstr("5 bytes after the checksum"));
}

TEST_F(VocabularyFileTest, ChecksumMismatch) {
  for (std::size_t offset : {std::size_t{40}, std::size_t{100}, bytes_.size() - 10}) {
    std::string bytes = bytes_;
    bytes[offset] = static_cast<char>(bytes[offset] ^ 0x10);
    EXPECT_THAT(LoadError(bytes), HasSubstr("checksum mismatch")) << "flipped byte " << offset;
  }
}

TEST_F(VocabularyFileTest, InconsistentCounts) {
  const auto nodes = static_cast<std::uint32_t>(vocabulary_.node_count());
  const auto words = static_cast<std::uint32_t>(vocabulary_.word_count());
  // Node count changed, payload size not: the header contradicts itself.
  EXPECT_THAT(LoadError(Resealed(With<std::uint32_t>(bytes_, 20, nodes - 1))), HasSubstr("inconsistent counts"));
  EXPECT_THAT(LoadError(Resealed(With<std::uint32_t>(bytes_, 24, words + 1))), HasSubstr("inconsistent counts"));
  // Root child count changed: the counts no longer describe a tree.
  std::string bytes = bytes_;
  bytes[64 + 32 * nodes] = 2;
  EXPECT_THAT(LoadError(Resealed(bytes)), HasSubstr("inconsistent tree"));
  // k out of range.
  EXPECT_THAT(LoadError(Resealed(With<std::uint32_t>(bytes_, 12, 1))), HasSubstr("offset 12"));
}

TEST_F(VocabularyFileTest, NonFiniteWeight) {
  const std::size_t last_weight = bytes_.size() - 8;
  EXPECT_THAT(LoadError(Resealed(With<float>(bytes_, last_weight, std::nanf("")))), HasSubstr("weight"));
  EXPECT_THAT(LoadError(Resealed(With<float>(bytes_, last_weight, -1.0f))), HasSubstr("weight"));
}

TEST_F(VocabularyFileTest, SaveLeavesNoPartialFileOnFailure) {
  EXPECT_THROW(SaveVocabulary(vocabulary_, dir_ / "no_such_dir" / "v.dlv"), InputError);
  EXPECT_THROW(SerializeVocabulary(Vocabulary()), Error);
}

TEST(ShippedVocabulary, IsFoundAndLoads) {
  const auto path = FindVocabulary();
  EXPECT_EQ(path.filename(), kShippedVocabularyName);
  TrainingSummary summary;
  const Vocabulary vocabulary = LoadVocabulary(path, &summary);
  EXPECT_EQ(vocabulary.branching(), 10);
  EXPECT_EQ(vocabulary.levels(), 5);
  EXPECT_GT(vocabulary.word_count(), 10000u);
  EXPECT_GT(summary.images, 0u);
}

}  // namespace
}  // namespace dlslam::place
