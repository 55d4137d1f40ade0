#pragma once
// CRC-32 (IEEE 802.3 / zlib polynomial, reflected, initial and final value
// 0xFFFFFFFF): the checksum of binary files we write (e.g. vocabularies).
// Table-driven, 8 bytes per step ("slicing by 8"): ~1-2 GB/s, so checking a
// few-MB file costs a few milliseconds.
//
//   uint32_t crc = Crc32(bytes);                    // whole buffer
//   uint32_t crc = Crc32Update(Crc32(a), b);        // == Crc32(a + b)

#include <cstdint>
#include <span>
#include <string_view>

namespace dlslam {

// Continues a CRC over more bytes: Crc32Update(Crc32(a), b) == Crc32(a + b).
std::uint32_t Crc32Update(std::uint32_t crc, std::span<const std::uint8_t> bytes);

inline std::uint32_t Crc32(std::span<const std::uint8_t> bytes) { return Crc32Update(0, bytes); }
inline std::uint32_t Crc32(std::string_view bytes) {
  return Crc32({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
}

}  // namespace dlslam
