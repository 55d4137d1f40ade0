#include "dlslam/io/jpeg_decode.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;

std::vector<std::uint8_t> Encode(const cv::Mat& image, bool progressive = false) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", image, bytes, {cv::IMWRITE_JPEG_QUALITY, 90, cv::IMWRITE_JPEG_PROGRESSIVE, progressive});
  return bytes;
}

cv::Mat Texture(int type) {
  cv::Mat image(120, 160, type);
  cv::randu(image, 0, 255);
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.5);
  return image;
}

TEST(DecodeJpeg, SamePixelsAsOpenCv) {
  for (const bool progressive : {false, true}) {
    for (const int type : {CV_8UC3, CV_8UC1}) {
      const std::vector<std::uint8_t> bytes = Encode(Texture(type), progressive);
      const JpegDecodeResult ours = DecodeJpeg(bytes, 20000);
      ASSERT_TRUE(ours.problem.empty()) << ours.problem;
      const cv::Mat theirs = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
      ASSERT_EQ(ours.image.type(), theirs.type());
      EXPECT_EQ(cv::norm(ours.image, theirs, cv::NORM_INF), 0.0) << "progressive " << progressive;
    }
  }
}

TEST(DecodeJpeg, CorruptEntropyDataIsRefusedNotGreyFilled) {
  std::vector<std::uint8_t> bytes = Encode(Texture(CV_8UC3));
  // Cut in the middle of the scan: OpenCV fills the rest with grey and warns.
  std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
  EXPECT_FALSE(cv::imdecode(cut, cv::IMREAD_UNCHANGED).empty());
  const JpegDecodeResult truncated = DecodeJpeg(cut, 20000);
  EXPECT_TRUE(truncated.image.empty());
  EXPECT_THAT(truncated.problem, HasSubstr("corrupt JPEG data"));
  // A marker-like byte pair inside the scan.
  std::vector<std::uint8_t> flipped = bytes;
  flipped[bytes.size() * 2 / 3] = 0xFF;
  flipped[bytes.size() * 2 / 3 + 1] = 0xD3;
  EXPECT_TRUE(DecodeJpeg(flipped, 20000).image.empty());
}

TEST(DecodeJpeg, HugeOrForeignHeadersAreRefusedBeforeAllocating) {
  const std::vector<std::uint8_t> bytes = Encode(Texture(CV_8UC3));
  EXPECT_THAT(DecodeJpeg(bytes, 100).problem, HasSubstr("160x120 px, more than 100 px"));
  EXPECT_THAT(DecodeJpeg(std::vector<std::uint8_t>{0xFF, 0xD8, 0xFF, 0xD9}, 20000).problem, HasSubstr("cannot decode JPEG"));
  EXPECT_THAT(DecodeJpeg(std::vector<std::uint8_t>{}, 20000).problem, HasSubstr("cannot decode JPEG"));
}

}  // namespace
}  // namespace dlslam::io
