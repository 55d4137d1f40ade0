#include "dlslam/io/image_io.h"

#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <span>
#include <string>

#include "dlslam/data/camera.h"
#include "dlslam/io/file_util.h"
#include "dlslam/io/image_integrity.h"
#include "dlslam/io/jpeg_decode.h"
#include "dlslam/io/png_decode.h"
#include "dlslam/util/check.h"

namespace dlslam::io {
namespace {

[[noreturn]] void Fail(const ImageSource& source, const char* kind, const std::string& problem) {
  throw InputError(source.list_file.empty() ? source.image : source.list_file, source.line,
                   "{} image '{}': {}", kind, ShortPath(source.image), problem);
}

// Larger than any RGB-D frame (a 4K 16-bit PNG stored raw is ~50 MB).
constexpr std::uintmax_t kMaxImageBytes = 256ull << 20;

// Reads the bytes ourselves (ReadFileBytes: regular files under 256 MB only)
// so that a missing, unreadable and empty file each get their own message
// (cv::imread reports all three as an empty Mat), and checks their
// structure: OpenCV decodes a truncated or corrupted file into grey pixels
// with only a warning.
cv::Mat Decode(const ImageSource& source, const char* kind, int flags) {
  std::string file;
  try {
    file = ReadFileBytes(source.image, kMaxImageBytes, "an image");
  } catch (const InputError& e) {
    Fail(source, kind, e.problem());  // named with the list line that referenced it
  }
  const std::span<const std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(file.data()), file.size());
  if (bytes.empty()) Fail(source, kind, "empty file (0 bytes)");
  if (const std::optional<std::string> problem = CheckImageIntegrity(bytes)) Fail(source, kind, *problem);
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    JpegDecodeResult jpeg = DecodeJpeg(bytes, kMaxImageSide);
    if (jpeg.image.empty()) Fail(source, kind, jpeg.problem);
    return jpeg.image;
  }
  if (flags == cv::IMREAD_UNCHANGED) {
    PngDecodeResult png = DecodePng(bytes, kMaxImageSide);
    if (!png.problem.empty()) Fail(source, kind, png.problem);
    if (!png.image.empty()) return png.image;
  }
  cv::Mat image;
  try {
    image = cv::imdecode(cv::Mat(1, static_cast<int>(bytes.size()), CV_8UC1, file.data()), flags);
  } catch (const cv::Exception& e) {
    Fail(source, kind, std::string("cannot decode: ") + e.what());
  }
  if (image.empty()) Fail(source, kind, "cannot decode (corrupt, truncated or not an image)");
  return image;
}

void CheckSize(const ImageSource& source, const char* kind, const cv::Mat& image, int width,
               int height) {
  if (width <= 0 || height <= 0) return;
  if (image.cols != width || image.rows != height) {
    Fail(source, kind,
         fmt::format("size {}x{} differs from the camera's {}x{}", image.cols, image.rows, width,
                     height));
  }
}

}  // namespace

cv::Mat ReadColorImage(const ImageSource& source, int width, int height) {
  cv::Mat image = Decode(source, "colour", cv::IMREAD_UNCHANGED);
  if (image.depth() != CV_8U) {
    Fail(source, "colour",
         fmt::format("{}-bit image, expected 8-bit colour (a depth image listed as colour?)",
                     image.elemSize1() * 8));
  }
  CheckSize(source, "colour", image, width, height);
  switch (image.channels()) {
    case 3:
      return image;
    case 4: {
      cv::Mat bgr;
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    }
    case 1: {
      cv::Mat bgr;
      cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    }
    default:
      Fail(source, "colour", fmt::format("{} channels, expected 1, 3 or 4", image.channels()));
  }
}

cv::Mat ReadDepthImage(const ImageSource& source, double depth_factor, int width, int height) {
  DLSLAM_CHECK(depth_factor > 0, "depth factor {} must be positive", depth_factor);
  const cv::Mat raw = Decode(source, "depth", cv::IMREAD_UNCHANGED);
  if (raw.channels() != 1) {
    Fail(source, "depth",
         fmt::format("{} channels, expected a single-channel 16-bit PNG (a colour image listed "
                     "as depth?)",
                     raw.channels()));
  }
  if (raw.depth() != CV_16U) {
    Fail(source, "depth",
         fmt::format("{}-bit image, expected 16-bit depth (an 8-bit mask or visualisation?)",
                     raw.elemSize1() * 8));
  }
  CheckSize(source, "depth", raw, width, height);
  cv::Mat metres;
  raw.convertTo(metres, CV_32F, 1.0 / depth_factor);
  return metres;
}

cv::Mat ReadMaskImage(const ImageSource& source, int width, int height) {
  const cv::Mat mask = Decode(source, "mask", cv::IMREAD_UNCHANGED);
  if (mask.channels() != 1) {
    Fail(source, "mask", fmt::format("{} channels, expected a single-channel 8-bit label image", mask.channels()));
  }
  if (mask.depth() != CV_8U) {
    Fail(source, "mask",
         fmt::format("{}-bit image, expected an 8-bit label image (a depth image listed as mask?)",
                     mask.elemSize1() * 8));
  }
  CheckSize(source, "mask", mask, width, height);
  return mask;
}

cv::Size ReadImageSize(const ImageSource& source) {
  return Decode(source, "colour", cv::IMREAD_UNCHANGED).size();
}

void WriteImage(const std::filesystem::path& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path.string(), image);
  } catch (const cv::Exception& e) {
    throw InputError(path, 0, "cannot write image: {}", e.what());
  }
  if (!ok) throw InputError(path, 0, "cannot write image");
}

}  // namespace dlslam::io
