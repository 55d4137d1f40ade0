#include "dlslam/io/png_decode.h"

#include <fmt/format.h>
#include <libdeflate.h>

#include "dlslam/io/png_format.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

namespace dlslam::io {
namespace {

bool IsChunk(const std::uint8_t* name, const char* expected) { return std::memcmp(name, expected, 4) == 0; }

struct Header {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, colour_type = 0;
  int channels = 0;  // 0 = a format not covered here
};

// Grey 8 / 16 bit, RGB 8 bit, RGBA 8 bit; compression, filter method and
// interlacing all 0 (the only values a dataset writer uses).
Header ReadHeader(const std::uint8_t* data) {
  Header h;
  h.width = BigEndian32(data);
  h.height = BigEndian32(data + 4);
  h.bit_depth = data[8];
  h.colour_type = data[9];
  if (data[10] != 0 || data[11] != 0 || data[12] != 0) return h;
  if (h.colour_type == 0 && (h.bit_depth == 8 || h.bit_depth == 16)) h.channels = 1;
  if (h.colour_type == 2 && h.bit_depth == 8) h.channels = 3;
  if (h.colour_type == 6 && h.bit_depth == 8) h.channels = 4;
  return h;
}

// The PNG spec's predictor: the neighbour (left a, up b, up-left c) closest
// to a + b - c, ties in the order a, b, c. Written to compile to selects.
inline int Paeth(int a, int b, int c) {
  const int pa = std::abs(b - c);
  const int pb = std::abs(a - c);
  const int pc = std::abs(a + b - 2 * c);
  const int b_or_c = pb <= pc ? b : c;
  return pa <= pb && pa <= pc ? a : b_or_c;
}

// Paeth with the left and up-left bytes of each of the kBpp interleaved
// byte lanes held in registers: the lanes' dependency chains then overlap
// and no byte waits for its own store to be read back. Not inlined: inside
// the decoder's loop the lanes spilled to the stack (2.25 vs 1.5 ms a frame).
template <int kBpp>
[[gnu::noinline]] void UndoPaeth(std::uint8_t* row, const std::uint8_t* prev, std::size_t n) {
  std::array<int, kBpp> a{}, c{};
  for (std::size_t i = 0; i < n; i += kBpp) {
    for (int k = 0; k < kBpp; ++k) {
      const int b = prev[i + k];
      a[k] = static_cast<std::uint8_t>(row[i + k] + Paeth(a[k], b, c[k]));
      row[i + k] = static_cast<std::uint8_t>(a[k]);
      c[k] = b;
    }
  }
}

// Reverses one row's filter in place; `prev` is the row above, already
// reconstructed (zeros for the first). False on an unknown filter type.
bool Unfilter(int type, std::uint8_t* row, const std::uint8_t* prev, std::size_t n, int bpp) {
  const auto step = static_cast<std::size_t>(bpp);
  switch (type) {
    case 0: return true;
    case 1:
      for (std::size_t i = step; i < n; ++i) row[i] = static_cast<std::uint8_t>(row[i] + row[i - step]);
      return true;
    case 2:
      for (std::size_t i = 0; i < n; ++i) row[i] = static_cast<std::uint8_t>(row[i] + prev[i]);
      return true;
    case 3:
      for (std::size_t i = 0; i < step; ++i) row[i] = static_cast<std::uint8_t>(row[i] + (prev[i] >> 1));
      for (std::size_t i = step; i < n; ++i) {
        row[i] = static_cast<std::uint8_t>(row[i] + ((row[i - step] + prev[i]) >> 1));
      }
      return true;
    case 4:
      switch (bpp) {
        case 1: UndoPaeth<1>(row, prev, n); return true;
        case 2: UndoPaeth<2>(row, prev, n); return true;
        case 3: UndoPaeth<3>(row, prev, n); return true;
        case 4: UndoPaeth<4>(row, prev, n); return true;
        default: return false;
      }
    default: return false;
  }
}

// One reconstructed row into OpenCV's layout: host-order 16-bit, BGR(A).
void StoreRow(const std::uint8_t* row, const Header& h, std::uint8_t* out) {
  const std::size_t w = h.width;
  if (h.bit_depth == 16) {
    auto* out16 = reinterpret_cast<std::uint16_t*>(out);
    for (std::size_t x = 0; x < w; ++x) {
      out16[x] = static_cast<std::uint16_t>((row[2 * x] << 8) | row[2 * x + 1]);
    }
    return;
  }
  if (h.channels == 1) {
    std::memcpy(out, row, w);
    return;
  }
  const auto channels = static_cast<std::size_t>(h.channels);
  for (std::size_t x = 0; x < w; ++x) {
    const std::uint8_t* in = row + channels * x;
    std::uint8_t* px = out + channels * x;
    px[0] = in[2];
    px[1] = in[1];
    px[2] = in[0];
    if (channels == 4) px[3] = in[3];
  }
}

struct DecompressorDeleter {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

}  // namespace

PngDecodeResult DecodePng(std::span<const std::uint8_t> bytes, int max_side) {
  PngDecodeResult result;
  if (!HasPngSignature(bytes)) return result;
  // The chunks: IHDR first, the IDATs' data concatenated, up to IEND.
  // Reused by the thread's next image: freshly allocated, their pages
  // faulted in on every call cost a third of the decode.
  thread_local std::vector<std::uint8_t> compressed, raw;
  compressed.clear();
  Header header;
  bool ended = false;
  for (std::size_t pos = kPngSignature.size(); !ended;) {
    if (pos + 12 > bytes.size()) return result;  // truncated: OpenCV's path reports it
    const std::uint32_t length = BigEndian32(&bytes[pos]);
    if (length > bytes.size() - pos - 12) return result;
    const std::uint8_t* name = &bytes[pos + 4];
    const std::uint8_t* data = &bytes[pos + 8];
    if (pos == kPngSignature.size()) {
      if (!IsChunk(name, "IHDR") || length != 13) return result;
      header = ReadHeader(data);
      if (header.channels == 0) return result;
    } else if (IsChunk(name, "IDAT")) {
      compressed.insert(compressed.end(), data, data + length);
    } else if (IsChunk(name, "IEND")) {
      ended = true;
    } else if (IsChunk(name, "PLTE") || IsChunk(name, "tRNS")) {
      return result;  // colours or transparency that libpng would apply
    }
    pos += 12 + length;
  }
  const auto max = static_cast<std::uint32_t>(max_side);
  if (header.width == 0 || header.height == 0 || header.width > max || header.height > max) return result;

  const int bpp = header.channels * header.bit_depth / 8;
  const std::size_t stride = static_cast<std::size_t>(header.width) * static_cast<std::size_t>(bpp);
  const std::size_t expected = (stride + 1) * header.height;
  raw.resize(expected);
  const std::unique_ptr<libdeflate_decompressor, DecompressorDeleter> decompressor(libdeflate_alloc_decompressor());
  if (!decompressor) throw std::bad_alloc();
  std::size_t produced = 0;
  const libdeflate_result status = libdeflate_zlib_decompress(decompressor.get(), compressed.data(), compressed.size(),
                                                               raw.data(), raw.size(), &produced);
  if (status == LIBDEFLATE_INSUFFICIENT_SPACE) return result;  // extra data: libpng only warns, let it decide
  if (status != LIBDEFLATE_SUCCESS) {
    result.problem = "corrupt PNG: the compressed image data (IDAT) is not a valid zlib stream";
    return result;
  }
  if (produced != expected) {
    result.problem = fmt::format("corrupt PNG: the image data holds {} bytes, {}x{} needs {}", produced,
                                 header.width, header.height, expected);
    return result;
  }

  const int type = header.bit_depth == 16 ? CV_16UC1 : CV_8UC(header.channels);
  cv::Mat image(static_cast<int>(header.height), static_cast<int>(header.width), type);
  const std::vector<std::uint8_t> zeros(stride, 0);
  const std::uint8_t* prev = zeros.data();
  for (std::uint32_t y = 0; y < header.height; ++y) {
    std::uint8_t* row = raw.data() + static_cast<std::size_t>(y) * (stride + 1);
    if (!Unfilter(row[0], row + 1, prev, stride, bpp)) {
      result.problem = fmt::format("corrupt PNG: row {} has filter type {} (valid: 0-4)", y, row[0]);
      return result;
    }
    StoreRow(row + 1, header, image.ptr<std::uint8_t>(static_cast<int>(y)));
    prev = row + 1;
  }
  result.image = image;
  return result;
}

}  // namespace dlslam::io
