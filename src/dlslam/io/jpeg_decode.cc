#include "dlslam/io/jpeg_decode.h"

#include <fmt/format.h>

#include <csetjmp>
#include <cstdio>
// jpeglib.h needs size_t and FILE declared first.
#include <jpeglib.h>

namespace dlslam::io {
namespace {

// libjpeg reports through callbacks: error_exit must not return (we
// longjmp back), emit_message(-1) is a warning about corrupt data.
struct ErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  std::string problem;
};

std::string MessageOf(j_common_ptr info) {
  char text[JMSG_LENGTH_MAX] = {};
  info->err->format_message(info, text);
  return text;
}

[[noreturn]] void OnError(j_common_ptr info) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  errors->problem = "cannot decode JPEG: " + MessageOf(info);
  std::longjmp(errors->jump, 1);
}

void OnMessage(j_common_ptr info, int level) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  if (level < 0 && errors->problem.empty()) errors->problem = MessageOf(info);  // warnings only
}

}  // namespace

JpegDecodeResult DecodeJpeg(std::span<const std::uint8_t> bytes, int max_side) {
  JpegDecodeResult result;
  jpeg_decompress_struct info{};
  ErrorManager errors{};
  info.err = jpeg_std_error(&errors.base);
  errors.base.error_exit = OnError;
  errors.base.emit_message = OnMessage;
  // Everything longjmp may skip lives above this line or in `result`; the
  // image is allocated only after the header, and freed by cv::Mat itself.
  if (setjmp(errors.jump) != 0) {
    jpeg_destroy_decompress(&info);
    result.image.release();
    result.problem = errors.problem;
    return result;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  if (static_cast<int>(info.image_width) > max_side || static_cast<int>(info.image_height) > max_side) {
    result.problem = fmt::format("JPEG of {}x{} px, more than {} px on a side", info.image_width,
                                 info.image_height, max_side);
    jpeg_destroy_decompress(&info);
    return result;
  }
  int type = CV_8UC3;
  if (info.jpeg_color_space == JCS_GRAYSCALE) {
    info.out_color_space = JCS_GRAYSCALE;
    type = CV_8UC1;
  } else if (info.num_components == 3) {
    info.out_color_space = JCS_EXT_BGR;
  } else {
    result.problem = fmt::format("JPEG with {} colour components (CMYK?), expected grey or colour",
                                 info.num_components);
    jpeg_destroy_decompress(&info);
    return result;
  }
  jpeg_start_decompress(&info);
  result.image.create(static_cast<int>(info.output_height), static_cast<int>(info.output_width), type);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = result.image.ptr<JSAMPLE>(static_cast<int>(info.output_scanline));
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  if (!errors.problem.empty()) {
    result.image.release();
    result.problem = "corrupt JPEG data: " + errors.problem;
  }
  return result;
}

}  // namespace dlslam::io
