#include "dlslam/datasets/digest.h"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <array>
#include <cctype>
#include <fstream>
#include <memory>
#include <vector>

#include "dlslam/util/check.h"

namespace dlslam::datasets {
namespace {

struct ContextDeleter {
  void operator()(EVP_MD_CTX* context) const { EVP_MD_CTX_free(context); }
};

class Hasher {
 public:
  explicit Hasher(DigestKind kind) : context_(EVP_MD_CTX_new()) {
    const EVP_MD* md = kind == DigestKind::kSha256 ? EVP_sha256() : EVP_md5();
    if (!context_ || EVP_DigestInit_ex(context_.get(), md, nullptr) != 1) {
      throw Error(fmt::format("OpenSSL cannot start a {} digest", DigestName(kind)));
    }
  }
  void Update(const char* data, std::size_t size) {
    if (EVP_DigestUpdate(context_.get(), data, size) != 1) throw Error("OpenSSL digest update failed");
  }
  std::string FinishHex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int length = 0;
    if (EVP_DigestFinal_ex(context_.get(), digest.data(), &length) != 1) {
      throw Error("OpenSSL digest finalisation failed");
    }
    std::string hex;
    for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
    return hex;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, ContextDeleter> context_;
};

}  // namespace

std::string_view DigestName(DigestKind kind) { return kind == DigestKind::kSha256 ? "sha256" : "md5"; }

std::string DigestHex(std::string_view bytes, DigestKind kind) {
  Hasher hasher(kind);
  hasher.Update(bytes.data(), bytes.size());
  return hasher.FinishHex();
}

std::string FileDigestHex(const std::filesystem::path& path, DigestKind kind) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open to compute its {}", DigestName(kind));
  Hasher hasher(kind);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    if (in.gcount() > 0) hasher.Update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(path, 0, "read error while computing its {}", DigestName(kind));
  return hasher.FinishHex();
}

std::string NormalizeHexDigest(std::string_view hex, DigestKind kind, std::string_view what) {
  const std::size_t expected = kind == DigestKind::kSha256 ? 64 : 32;
  std::string out;
  for (const char c : hex) {
    if (!std::isxdigit(static_cast<unsigned char>(c))) {
      throw Error(fmt::format("{} '{}' is not hexadecimal", what, hex));
    }
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  if (out.size() != expected) {
    throw Error(fmt::format("{} '{}' has {} hex digits, a {} has {}", what, hex, out.size(),
                            DigestName(kind), expected));
  }
  return out;
}

}  // namespace dlslam::datasets
