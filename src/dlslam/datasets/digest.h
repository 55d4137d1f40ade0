#pragma once
// Archive checksums (OpenSSL EVP), streamed so multi-GB files need no memory.

#include <filesystem>
#include <string>
#include <string_view>

namespace dlslam::datasets {

enum class DigestKind { kSha256, kMd5 };

std::string_view DigestName(DigestKind kind);  // "sha256" / "md5"

// Lower-case hex digest of a file's bytes; throws InputError when unreadable.
std::string FileDigestHex(const std::filesystem::path& path, DigestKind kind);
// Lower-case hex digest of a byte string.
std::string DigestHex(std::string_view bytes, DigestKind kind);

// Lower-cases a user-given hex digest and checks its length (64 for sha256,
// 32 for md5) and characters; throws dlslam::Error naming `what` otherwise.
std::string NormalizeHexDigest(std::string_view hex, DigestKind kind, std::string_view what);

}  // namespace dlslam::datasets
