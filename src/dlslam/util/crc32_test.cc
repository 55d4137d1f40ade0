#include "dlslam/util/crc32.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace dlslam {
namespace {

// Bit-by-bit reference straight from the definition (no tables).
std::uint32_t Crc32BitByBit(std::string_view bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char c : bytes) {
    crc ^= c;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 1u) ? (crc >> 1) ^ 0xEDB88320u : crc >> 1;
  }
  return ~crc;
}

TEST(Crc32, MatchesPublishedCheckValues) {
  // The standard check value of CRC-32/ISO-HDLC (zlib's crc32) for "123456789".
  EXPECT_EQ(Crc32("123456789"), 0xCBF43926u);
  EXPECT_EQ(Crc32(""), 0u);
  // zlib: crc32("The quick brown fox jumps over the lazy dog") = 0x414FA339.
  EXPECT_EQ(Crc32("The quick brown fox jumps over the lazy dog"), 0x414FA339u);
}

TEST(Crc32, MatchesBitwiseReferenceForAllLengthsAndOffsets) {
  std::string data;
  for (int i = 0; i < 300; ++i) data.push_back(static_cast<char>((i * 131 + 7) & 0xFF));
  for (std::size_t offset = 0; offset < 9; ++offset) {
    for (std::size_t length = 0; offset + length <= data.size(); length += 7) {
      const std::string_view piece(data.data() + offset, length);
      ASSERT_EQ(Crc32(piece), Crc32BitByBit(piece)) << "offset " << offset << " length " << length;
    }
  }
}

TEST(Crc32, UpdateContinuesAcrossSplits) {
  const std::string data = "vocabulary bytes split at every position";
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(data.data());
  for (std::size_t split = 0; split <= data.size(); ++split) {
    const std::uint32_t first = Crc32Update(0, {bytes, split});
    EXPECT_EQ(Crc32Update(first, {bytes + split, data.size() - split}), Crc32(data));
  }
}

TEST(Crc32, DetectsSingleBitFlips) {
  std::string data(64, 'x');
  const std::uint32_t clean = Crc32(data);
  for (std::size_t i = 0; i < data.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::string flipped = data;
      flipped[i] = static_cast<char>(flipped[i] ^ (1 << bit));
      ASSERT_NE(Crc32(flipped), clean);
    }
  }
}

}  // namespace
}  // namespace dlslam
