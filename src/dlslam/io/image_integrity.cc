#include "dlslam/data/camera.h"
#include "dlslam/io/image_integrity.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "dlslam/io/png_format.h"
#include "dlslam/util/crc32.h"

namespace dlslam::io {
namespace {

std::string ChunkName(const std::uint8_t* p) {
  std::string name(reinterpret_cast<const char*>(p), 4);
  for (char& c : name) {
    if (c < 32 || c > 126) c = '?';
  }
  return name;
}

std::optional<std::string> CheckPng(std::span<const std::uint8_t> b) {
  std::size_t pos = 8;  // after the signature
  int chunks = 0;
  while (true) {
    if (pos + 12 > b.size()) {
      return fmt::format("truncated PNG: ends at byte {} before the IEND chunk ({} chunks read)", b.size(), chunks);
    }
    const std::uint32_t length = BigEndian32(&b[pos]);
    const std::string name = ChunkName(&b[pos + 4]);
    if (length > b.size() - pos - 12) {
      return fmt::format("truncated PNG: chunk '{}' at byte {} claims {} bytes, the file has {}", name, pos, length,
                         b.size() - pos - 12);
    }
    const std::uint32_t stored = BigEndian32(&b[pos + 8 + length]);
    const std::uint32_t computed = Crc32(b.subspan(pos + 4, length + 4));
    if (stored != computed) {
      return fmt::format("corrupt PNG: chunk '{}' at byte {} fails its CRC check", name, pos);
    }
    if (name == "IHDR" && length >= 8) {
      // Refused before OpenCV allocates width x height (a 100 KB file may claim 10^9 pixels).
      const std::uint32_t width = BigEndian32(&b[pos + 8]), height = BigEndian32(&b[pos + 12]);
      if (width > static_cast<std::uint32_t>(kMaxImageSide) || height > static_cast<std::uint32_t>(kMaxImageSide)) {
        return fmt::format("PNG of {}x{} px, more than {} px on a side", width, height, kMaxImageSide);
      }
    }
    ++chunks;
    pos += 12 + length;
    if (name == "IEND") return std::nullopt;
  }
}

std::optional<std::string> CheckJpeg(std::span<const std::uint8_t> b) {
  std::size_t pos = 2;  // after SOI
  while (true) {
    // The next marker: FF (fill bytes FF allowed) then its code.
    if (pos + 2 > b.size()) return fmt::format("truncated JPEG: ends at byte {} before the EOI marker", b.size());
    if (b[pos] != 0xFF) return fmt::format("corrupt JPEG: no marker at byte {} (0x{:02X})", pos, b[pos]);
    while (pos + 1 < b.size() && b[pos + 1] == 0xFF) ++pos;
    if (pos + 2 > b.size()) return fmt::format("truncated JPEG: ends at byte {} before the EOI marker", b.size());
    const std::uint8_t code = b[pos + 1];
    pos += 2;
    if (code == 0xD9) return std::nullopt;  // EOI
    if (code == 0x00 || code == 0xD8 || (code >= 0xD0 && code <= 0xD7) || code == 0x01) {
      return fmt::format("corrupt JPEG: unexpected marker 0x{:02X} at byte {}", code, pos - 2);
    }
    if (pos + 2 > b.size()) return fmt::format("truncated JPEG: ends inside marker 0x{:02X}", code);
    const std::size_t length = (std::size_t{b[pos]} << 8) | b[pos + 1];
    if (length < 2 || pos + length > b.size()) {
      return fmt::format("truncated JPEG: segment 0x{:02X} at byte {} claims {} bytes, the file has {}", code, pos - 2,
                         length, b.size() - pos);
    }
    pos += length;
    if (code != 0xDA) continue;  // not SOS: the next marker follows
    // Entropy-coded data: FF is followed by a stuffed 00 or a restart
    // marker, or begins the next marker.
    while (true) {
      const auto next = std::find(b.begin() + static_cast<std::ptrdiff_t>(pos), b.end(), std::uint8_t{0xFF});
      pos = static_cast<std::size_t>(next - b.begin());
      if (pos + 1 >= b.size()) {
        return fmt::format("truncated JPEG: ends at byte {} inside the compressed data", b.size());
      }
      const std::uint8_t after = b[pos + 1];
      if (after == 0x00 || (after >= 0xD0 && after <= 0xD7) || after == 0xFF) {
        pos += after == 0xFF ? 1 : 2;
        continue;
      }
      break;  // a marker: back to the segment loop
    }
  }
}

}  // namespace

std::optional<std::string> CheckImageIntegrity(std::span<const std::uint8_t> bytes) {
  if (HasPngSignature(bytes)) return CheckPng(bytes);
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return CheckJpeg(bytes);
  return std::nullopt;
}

}  // namespace dlslam::io
