#include "dlslam/io/ply_writer.h"

#include <bit>
#include <cstring>
#include <ostream>

#include "dlslam/io/file_util.h"

namespace dlslam::io {

void WritePointCloudPly(const std::filesystem::path& path, const std::vector<ColouredPoint>& points) {
  static_assert(std::endian::native == std::endian::little, "the PLY writer writes the host's floats as they are");
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\ncomment written by DLSLAM\nelement vertex " << points.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
    constexpr std::size_t kRecord = 3 * sizeof(float) + 3;
    std::vector<char> buffer(kRecord * points.size());
    char* at = buffer.data();
    for (const ColouredPoint& p : points) {
      std::memcpy(at, p.position.data(), 3 * sizeof(float));
      std::memcpy(at + 3 * sizeof(float), p.rgb.data(), 3);
      at += kRecord;
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  });
}

}  // namespace dlslam::io
