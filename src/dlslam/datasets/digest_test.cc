#include "dlslam/datasets/digest.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::datasets {
namespace {

TEST(Digest, KnownTestVectors) {
  // FIPS 180-2 appendix B.1 and RFC 1321 appendix A.5.
  EXPECT_EQ(DigestHex("abc", DigestKind::kSha256),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(DigestHex("", DigestKind::kSha256),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(DigestHex("abc", DigestKind::kMd5), "900150983cd24fb0d6963f7d28e17f72");
  EXPECT_EQ(DigestHex("message digest", DigestKind::kMd5), "f96b697d7cb7938d525a2f31aaf161d0");
}

TEST(Digest, FileDigestMatchesBytesAcrossBufferBoundaries) {
  const auto dir = testing::MakeTempDir("digest");
  std::string bytes(3 * (1 << 20) + 17, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 7919) % 251);
  std::ofstream(dir / "blob", std::ios::binary) << bytes;
  EXPECT_EQ(FileDigestHex(dir / "blob", DigestKind::kSha256), DigestHex(bytes, DigestKind::kSha256));
  EXPECT_EQ(FileDigestHex(dir / "blob", DigestKind::kMd5), DigestHex(bytes, DigestKind::kMd5));
  EXPECT_THROW(FileDigestHex(dir / "missing", DigestKind::kSha256), InputError);
  std::filesystem::remove_all(dir);
}

TEST(Digest, NormalizesUserHex) {
  EXPECT_EQ(NormalizeHexDigest("900150983CD24FB0D6963F7D28E17F72", DigestKind::kMd5, "--md5"),
            "900150983cd24fb0d6963f7d28e17f72");
  EXPECT_THROW(NormalizeHexDigest("abc", DigestKind::kMd5, "--md5"), Error);
  EXPECT_THROW(NormalizeHexDigest(std::string(64, 'g'), DigestKind::kSha256, "--sha256"), Error);
  try {
    NormalizeHexDigest("1234", DigestKind::kSha256, "--sha256");
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("--sha256 '1234' has 4 hex digits, a sha256 has 64"));
  }
}

}  // namespace
}  // namespace dlslam::datasets
