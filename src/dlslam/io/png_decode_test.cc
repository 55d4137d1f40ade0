#include "dlslam/io/png_decode.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <libdeflate.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <tuple>
#include <vector>

#include "dlslam/util/crc32.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;
using Bytes = std::vector<std::uint8_t>;

constexpr int kMaxSide = 20000;

void Put32(Bytes* out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<std::uint8_t>(v >> shift));
}

void PutChunk(Bytes* out, const char* name, const Bytes& data) {
  Put32(out, static_cast<std::uint32_t>(data.size()));
  Bytes body(name, name + 4);
  body.insert(body.end(), data.begin(), data.end());
  out->insert(out->end(), body.begin(), body.end());
  Put32(out, Crc32(body));
}

Bytes Compress(const Bytes& raw) {
  libdeflate_compressor* compressor = libdeflate_alloc_compressor(6);
  Bytes out(libdeflate_zlib_compress_bound(compressor, raw.size()));
  out.resize(libdeflate_zlib_compress(compressor, raw.data(), raw.size(), out.data(), out.size()));
  libdeflate_free_compressor(compressor);
  return out;
}

int PaethOf(int a, int b, int c) {  // the spec's reference formulation
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  if (pb <= pc) return b;
  return c;
}

// A PNG written by hand from big-endian sample bytes (`rows` x `stride`),
// row y filtered with filter type filter_of(y): every filter, at every
// bytes-per-pixel, whatever libpng's encoder would have chosen.
struct Spec {
  int width = 0, height = 0, bit_depth = 8, colour_type = 0, interlace = 0;
  std::vector<Bytes> extra_chunks_before_idat;  // name (4 bytes) + data
};

Bytes WritePng(const Spec& spec, const Bytes& samples, const std::function<int(int)>& filter_of,
               std::size_t idat_pieces = 1) {
  const int channels = spec.colour_type == 2 ? 3 : spec.colour_type == 6 ? 4 : spec.colour_type == 4 ? 2 : 1;
  const int bpp = std::max(1, channels * spec.bit_depth / 8);
  const std::size_t stride = (static_cast<std::size_t>(spec.width) * channels * spec.bit_depth + 7) / 8;
  Bytes raw;
  for (int y = 0; y < spec.height; ++y) {
    const std::uint8_t* row = &samples[static_cast<std::size_t>(y) * stride];
    const std::uint8_t* prev = y > 0 ? row - stride : nullptr;
    const int type = filter_of(y);
    raw.push_back(static_cast<std::uint8_t>(type));
    for (std::size_t i = 0; i < stride; ++i) {
      const int a = i >= static_cast<std::size_t>(bpp) ? row[i - static_cast<std::size_t>(bpp)] : 0;
      const int b = prev ? prev[i] : 0;
      const int c = prev && i >= static_cast<std::size_t>(bpp) ? prev[i - static_cast<std::size_t>(bpp)] : 0;
      const int predictor = type == 1 ? a : type == 2 ? b : type == 3 ? (a + b) / 2 : type == 4 ? PaethOf(a, b, c) : 0;
      raw.push_back(static_cast<std::uint8_t>(row[i] - predictor));
    }
  }
  Bytes png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  Bytes ihdr;
  Put32(&ihdr, static_cast<std::uint32_t>(spec.width));
  Put32(&ihdr, static_cast<std::uint32_t>(spec.height));
  for (int v : {spec.bit_depth, spec.colour_type, 0, 0, spec.interlace}) ihdr.push_back(static_cast<std::uint8_t>(v));
  PutChunk(&png, "IHDR", ihdr);
  for (const Bytes& chunk : spec.extra_chunks_before_idat) {
    PutChunk(&png, reinterpret_cast<const char*>(chunk.data()), Bytes(chunk.begin() + 4, chunk.end()));
  }
  const Bytes compressed = Compress(raw);
  const std::size_t piece = compressed.size() / idat_pieces + 1;
  for (std::size_t start = 0; start < compressed.size(); start += piece) {
    const std::size_t end = std::min(compressed.size(), start + piece);
    PutChunk(&png, "IDAT", Bytes(compressed.begin() + static_cast<std::ptrdiff_t>(start),
                                 compressed.begin() + static_cast<std::ptrdiff_t>(end)));
  }
  PutChunk(&png, "IEND", {});
  return png;
}

Bytes Samples(std::size_t n, unsigned seed) {
  // Smooth runs with noise, so that every filter sees carries and wraps.
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> noise(-40, 40);
  Bytes out(n);
  int value = 128;
  for (std::size_t i = 0; i < n; ++i) {
    value = std::clamp(value + noise(rng), 0, 255);
    out[i] = static_cast<std::uint8_t>(i % 7 == 0 ? rng() : value);
  }
  return out;
}

void ExpectSameAsOpenCv(const Bytes& png, int expected_type) {
  const PngDecodeResult ours = DecodePng(png, kMaxSide);
  ASSERT_TRUE(ours.problem.empty()) << ours.problem;
  ASSERT_FALSE(ours.image.empty());
  const cv::Mat theirs = cv::imdecode(png, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(theirs.empty());
  ASSERT_EQ(ours.image.type(), expected_type);
  ASSERT_EQ(theirs.type(), expected_type);
  ASSERT_EQ(ours.image.size(), theirs.size());
  EXPECT_EQ(cv::norm(ours.image, theirs, cv::NORM_INF), 0.0);
}

TEST(DecodePng, EveryFilterAtEveryCoveredFormatMatchesOpenCv) {
  struct Format {
    int bit_depth, colour_type, cv_type, bytes_per_pixel;
  };
  for (const Format f : {Format{16, 0, CV_16UC1, 2}, Format{8, 0, CV_8UC1, 1}, Format{8, 2, CV_8UC3, 3},
                         Format{8, 6, CV_8UC4, 4}}) {
    for (int filter = 0; filter <= 5; ++filter) {  // 5: a different filter on every row
      SCOPED_TRACE(::testing::Message() << "colour type " << f.colour_type << ", " << f.bit_depth << " bit, filter "
                                        << filter);
      Spec spec;
      spec.width = 37;
      spec.height = 23;
      spec.bit_depth = f.bit_depth;
      spec.colour_type = f.colour_type;
      const Bytes samples = Samples(static_cast<std::size_t>(spec.width * spec.height * f.bytes_per_pixel),
                                    static_cast<unsigned>(filter + 10 * f.colour_type));
      ExpectSameAsOpenCv(WritePng(spec, samples, [filter](int y) { return filter < 5 ? filter : y % 5; }, 3),
                         f.cv_type);
    }
  }
}

TEST(DecodePng, ImagesOpenCvEncodesDecodeToTheSamePixels) {
  cv::Mat depth(48, 64, CV_16UC1);
  cv::randu(depth, 0, 65535);
  cv::GaussianBlur(depth, depth, cv::Size(5, 5), 2.0);
  cv::Mat colour(48, 64, CV_8UC3);
  cv::randu(colour, 0, 255);
  cv::Mat bgra;
  cv::cvtColor(colour, bgra, cv::COLOR_BGR2BGRA);
  cv::Mat grey;
  cv::cvtColor(colour, grey, cv::COLOR_BGR2GRAY);
  for (const cv::Mat& image : {depth, colour, bgra, grey}) {
    for (const int level : {0, 1, 3, 9}) {
      for (const int strategy : {cv::IMWRITE_PNG_STRATEGY_DEFAULT, cv::IMWRITE_PNG_STRATEGY_FILTERED,
                                 cv::IMWRITE_PNG_STRATEGY_RLE}) {
        Bytes png;
        ASSERT_TRUE(cv::imencode(".png", image, png, {cv::IMWRITE_PNG_COMPRESSION, level, cv::IMWRITE_PNG_STRATEGY,
                                                      strategy}));
        ExpectSameAsOpenCv(png, image.type());
      }
    }
  }
}

TEST(DecodePng, RealBonnDepthFramesMatchOpenCv) {
  const auto shared = testing::SharedDataDir();
  if (!shared) GTEST_SKIP() << "../shared/data not found: the real Bonn frames are not there";
  const std::filesystem::path folder = *shared / "bonn/rgbd_bonn_crowd_280-579/depth";
  if (!std::filesystem::exists(folder)) GTEST_SKIP() << folder << " not found";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 20u);
  for (std::size_t i = 0; i < files.size(); i += files.size() / 20) {
    std::ifstream in(files[i], std::ios::binary);
    const Bytes png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    SCOPED_TRACE(files[i].string());
    ExpectSameAsOpenCv(png, CV_16UC1);
  }
}

TEST(DecodePng, OtherFormatsAreLeftToOpenCv) {
  const auto not_covered = [](const Bytes& png) {
    const PngDecodeResult r = DecodePng(png, kMaxSide);
    return !r.covered();
  };
  const auto plain = [](int y) { return y % 5; };
  Spec spec;
  spec.width = 8;
  spec.height = 4;
  // 16-bit colour, grey + alpha, 4-bit grey, interlaced.
  for (const auto& [depth, type, interlace] : {std::tuple{16, 2, 0}, {8, 4, 0}, {4, 0, 0}, {8, 0, 1}}) {
    spec.bit_depth = depth;
    spec.colour_type = type;
    spec.interlace = interlace;
    const std::size_t bits = static_cast<std::size_t>(spec.width * spec.height) * depth * (type == 2 ? 3 : type == 4 ? 2 : 1);
    EXPECT_TRUE(not_covered(WritePng(spec, Samples(bits / 8, 1), plain))) << depth << " bit, type " << type;
  }
  // Transparency libpng would turn into alpha.
  spec = {};
  spec.width = 8;
  spec.height = 4;
  spec.colour_type = 0;
  spec.extra_chunks_before_idat = {Bytes{'t', 'R', 'N', 'S', 0, 7}};
  EXPECT_TRUE(not_covered(WritePng(spec, Samples(32, 2), plain)));
  // Not a PNG at all, or only its signature.
  EXPECT_TRUE(not_covered(Bytes{0xFF, 0xD8, 0xFF, 0xD9}));
  EXPECT_TRUE(not_covered(Bytes{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A}));
  EXPECT_TRUE(not_covered({}));
}

TEST(DecodePng, ACoveredButDamagedImageNamesItsProblem) {
  Spec spec;
  spec.width = 16;
  spec.height = 8;
  spec.bit_depth = 16;
  const Bytes samples = Samples(16 * 8 * 2, 3);
  // An unknown filter type on row 5.
  EXPECT_THAT(DecodePng(WritePng(spec, samples, [](int y) { return y == 5 ? 9 : 1; }), kMaxSide).problem,
              HasSubstr("row 5 has filter type 9"));
  // Image data for fewer rows than the header claims.
  Bytes short_png = WritePng(spec, samples, [](int) { return 0; });
  short_png[8 + 8 + 7] = 9;  // IHDR height's low byte; CRCs are not checked here
  EXPECT_THAT(DecodePng(short_png, kMaxSide).problem, HasSubstr("holds 264 bytes, 16x9 needs 297"));
  // A broken zlib stream.
  Bytes broken = WritePng(spec, samples, [](int) { return 2; });
  const std::size_t idat = 8 + 25;  // after the signature and IHDR
  broken[idat + 8 + 2] = 0x07;  // the first deflate block: reserved type 3
  EXPECT_THAT(DecodePng(broken, kMaxSide).problem, HasSubstr("not a valid zlib stream"));
  // Larger than allowed: refused before allocating, left to the caller.
  EXPECT_FALSE(DecodePng(WritePng(spec, samples, [](int) { return 0; }), 15).covered());
}

TEST(DecodePng, NoTruncationOrByteFlipCrashesOrYieldsAWrongSizedImage) {
  Spec spec;
  spec.width = 24;
  spec.height = 12;
  spec.bit_depth = 16;
  const Bytes png = WritePng(spec, Samples(24 * 12 * 2, 4), [](int y) { return y % 5; }, 2);
  for (std::size_t n = 0; n < png.size(); ++n) {
    const PngDecodeResult r = DecodePng(std::span(png.data(), n), kMaxSide);
    EXPECT_TRUE(r.image.empty()) << "a file cut at byte " << n << " of " << png.size() << " decoded";
  }
  std::mt19937 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    Bytes flipped = png;
    flipped[rng() % flipped.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    const PngDecodeResult r = DecodePng(flipped, kMaxSide);
    if (r.image.empty()) continue;
    // What decodes (a flip in a CRC or inside the pixels' stored bytes
    // that zlib cannot see: stored blocks) still has the header's shape.
    EXPECT_EQ(r.image.type(), CV_16UC1);
    EXPECT_LE(r.image.total(), 24u * 12u * 256u);
  }
}

}  // namespace
}  // namespace dlslam::io
