#pragma once
// PNG decoding for the images RGB-D datasets store: 16-bit grey depth,
// 8-bit grey masks, 8-bit RGB(A) colour, non-interlaced. libpng (behind
// cv::imdecode) takes 3.1 ms for one 640x480 Bonn depth frame, most of it in
// zlib and the Paeth filter; libdeflate's inflate and a branch-free Paeth
// here take about half of that (1.4 ms). The reader thread decodes two images a
// frame on a 2-core machine, so this is CPU the tracker and the network get
// back.
//
// Anything else (palette, 1-4 bit grey, 16-bit colour, grey + alpha,
// interlacing, transparency chunks) is not covered: the caller falls back to
// OpenCV. The pixels are exactly cv::imdecode(bytes, IMREAD_UNCHANGED)'s.

#include <cstdint>
#include <opencv2/core.hpp>
#include <span>
#include <string>

namespace dlslam::io {

struct PngDecodeResult {
  // CV_16UC1 (host byte order), CV_8UC1, CV_8UC3 BGR or CV_8UC4 BGRA; empty
  // when not decoded here.
  cv::Mat image;
  // Why a covered file could not be decoded (a bad zlib stream, image data
  // shorter than the header's size, an unknown row filter), e.g. "corrupt PNG: row 57
  // has filter type 9". Empty with an empty image: not covered, decode it
  // elsewhere.
  std::string problem;

  bool covered() const { return !image.empty() || !problem.empty(); }
};

// `bytes` must be a whole PNG file. Chunk CRCs are not checked here
// (CheckImageIntegrity does); every length and offset is. A side above
// `max_side` px is refused before allocating.
PngDecodeResult DecodePng(std::span<const std::uint8_t> bytes, int max_side);

}  // namespace dlslam::io
