#pragma once
// JPEG decoding with libjpeg directly, so that its warnings count. Through
// cv::imdecode a byte flip inside the entropy-coded data ("Corrupt JPEG data:
// premature end of data segment", "extraneous bytes before marker") only
// prints a line on stderr and yields a grey-filled frame, which the tracker
// then takes for real. Here every warning refuses the image.

#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>

namespace dlslam::io {

struct JpegDecodeResult {
  cv::Mat image;        // CV_8UC3 BGR or CV_8UC1; empty when refused
  std::string problem;  // why not, e.g. "corrupt JPEG data: premature end of data segment"
};

// Decodes a baseline or progressive JPEG (greyscale or YCbCr/RGB). A
// libjpeg error or warning, a side above `max_side` px (checked from the
// header, before any allocation) or another colour space (CMYK) gives an
// empty image and the reason.
JpegDecodeResult DecodeJpeg(std::span<const std::uint8_t> bytes, int max_side);

}  // namespace dlslam::io
