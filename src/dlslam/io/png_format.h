#pragma once
// The bytes of a PNG file both its structure check (image_integrity) and its
// decoder (png_decode) read: the signature and big-endian chunk fields.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

namespace dlslam::io {

inline constexpr std::array<std::uint8_t, 8> kPngSignature = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};

inline bool HasPngSignature(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= kPngSignature.size() && std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin());
}

// A chunk's length, a header field or a CRC.
inline std::uint32_t BigEndian32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

}  // namespace dlslam::io
