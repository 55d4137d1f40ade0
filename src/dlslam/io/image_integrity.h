#pragma once
// Structural checks of compressed image files before decoding. OpenCV's
// decoders fill a truncated or corrupted JPEG or PNG with grey and report it
// only as a warning on stderr, so a damaged frame would be tracked as if it
// were real. We walk the file's own structure instead:
//   PNG:  every chunk's length within the file and its CRC-32 right, up to IEND;
//   JPEG: every marker segment within the file, entropy-coded data holding
//         only stuffed bytes, restart markers or the next marker, up to EOI.
// Byte flips inside JPEG entropy-coded data that form no marker are not seen
// (only a full decode could tell); every truncation and every PNG change is.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace dlslam::io {

// nullopt when the bytes are a structurally sound PNG or JPEG, or another
// format (not checked here); else what is wrong, e.g. "truncated PNG: ends
// inside chunk 'IDAT' at byte 5120 of 8000".
std::optional<std::string> CheckImageIntegrity(std::span<const std::uint8_t> bytes);

}  // namespace dlslam::io
