#include "dlslam/io/image_integrity.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <vector>

namespace dlslam::io {
namespace {

// A textured 160x120 image, encoded.
std::vector<std::uint8_t> Encoded(const std::string& ext, int type = CV_8UC3) {
  cv::Mat image(120, 160, type);
  cv::randu(image, cv::Scalar::all(0), cv::Scalar::all(type == CV_16UC1 ? 20000 : 255));
  std::vector<std::uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes));
  return bytes;
}

TEST(ImageIntegrity, SoundFilesPass) {
  EXPECT_EQ(CheckImageIntegrity(Encoded(".png")), std::nullopt);
  EXPECT_EQ(CheckImageIntegrity(Encoded(".png", CV_16UC1)), std::nullopt);
  EXPECT_EQ(CheckImageIntegrity(Encoded(".jpg")), std::nullopt);
  EXPECT_EQ(CheckImageIntegrity(Encoded(".jpg", CV_8UC1)), std::nullopt);
  // Other formats are the decoder's business.
  EXPECT_EQ(CheckImageIntegrity(Encoded(".bmp")), std::nullopt);
}

// Property: every truncation of a PNG or JPEG is refused, whatever the cut.
TEST(ImageIntegrity, EveryTruncationIsRefused) {
  std::mt19937 rng(7);
  for (const char* ext : {".png", ".jpg"}) {
    const std::vector<std::uint8_t> bytes = Encoded(ext);
    for (int trial = 0; trial < 200; ++trial) {
      const std::size_t keep = 3 + rng() % (bytes.size() - 3);
      const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(keep));
      EXPECT_NE(CheckImageIntegrity(cut), std::nullopt) << ext << " cut to " << keep << " of " << bytes.size();
    }
  }
}

// Property: any changed byte of a PNG is refused (CRC), seeded random flips.
TEST(ImageIntegrity, EveryPngByteFlipIsRefused) {
  const std::vector<std::uint8_t> bytes = Encoded(".png", CV_16UC1);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<std::uint8_t> flipped = bytes;
    const std::size_t at = 8 + rng() % (bytes.size() - 8);  // after the signature
    flipped[at] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    EXPECT_NE(CheckImageIntegrity(flipped), std::nullopt) << "byte " << at;
  }
}

// JPEG: flips that break the marker structure are refused; the others
// (inside the compressed data) cannot be seen without decoding: measured,
// not promised.
TEST(ImageIntegrity, JpegFlipsOfTheStructureAreRefused) {
  std::vector<std::uint8_t> bytes = Encoded(".jpg");
  std::vector<std::uint8_t> no_eoi(bytes.begin(), bytes.end() - 2);
  EXPECT_NE(CheckImageIntegrity(no_eoi), std::nullopt);
  std::vector<std::uint8_t> bad_marker = bytes;
  bad_marker[3] = 0xD8;  // the first segment's marker turned into a second SOI
  EXPECT_NE(CheckImageIntegrity(bad_marker), std::nullopt);
  std::vector<std::uint8_t> long_segment = bytes;
  long_segment[4] = 0xFF;  // the first segment's length beyond the file
  long_segment[5] = 0xFF;
  EXPECT_NE(CheckImageIntegrity(long_segment), std::nullopt);
}

TEST(ImageIntegrity, TinyAndEmptyInputs) {
  EXPECT_EQ(CheckImageIntegrity({}), std::nullopt);  // the caller refuses empty files
  const std::vector<std::uint8_t> png_signature = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  EXPECT_NE(CheckImageIntegrity(png_signature), std::nullopt);
  const std::vector<std::uint8_t> jpeg_start = {0xFF, 0xD8, 0xFF};
  EXPECT_NE(CheckImageIntegrity(jpeg_start), std::nullopt);
}

}  // namespace
}  // namespace dlslam::io
