#include "dlslam/io/ply_writer.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

TEST(PlyWriter, WritesAHeaderAndOneRecordPerPoint) {
  const std::filesystem::path path = testing::MakeTempDir("ply_writer") / "cloud.ply";
  std::vector<ColouredPoint> points = {{Eigen::Vector3f(1.5f, -2.0f, 3.25f), {255, 128, 0}},
                                       {Eigen::Vector3f(0.0f, 0.5f, -1.0f), {1, 2, 3}}};
  WritePointCloudPly(path, points);
  std::ifstream in(path, std::ios::binary);
  std::stringstream all;
  all << in.rdbuf();
  const std::string bytes = all.str();
  const std::string end = "end_header\n";
  const std::size_t body = bytes.find(end);
  ASSERT_NE(body, std::string::npos);
  const std::string header = bytes.substr(0, body);
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(header.find("element vertex 2\n"), std::string::npos);
  ASSERT_EQ(bytes.size(), body + end.size() + 2 * 15);
  float xyz[3];
  std::memcpy(xyz, bytes.data() + body + end.size() + 15, sizeof(xyz));
  EXPECT_EQ(xyz[0], 0.0f);
  EXPECT_EQ(xyz[1], 0.5f);
  EXPECT_EQ(xyz[2], -1.0f);
  EXPECT_EQ(static_cast<unsigned char>(bytes[body + end.size() + 12]), 255);
  EXPECT_EQ(static_cast<unsigned char>(bytes[body + end.size() + 29]), 3);
}

TEST(PlyWriter, AnUnwritablePathIsAnInputError) {
  EXPECT_THROW(WritePointCloudPly("/nonexistent-folder/cloud.ply", {}), InputError);
}

}  // namespace
}  // namespace dlslam::io
