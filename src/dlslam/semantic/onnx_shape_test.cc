// DeclaredInputSize on real exports, on hand-built protobuf messages, and on
// every truncation and random corruption we can afford.

#include "dlslam/semantic/onnx_shape.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "dlslam/semantic/segmenter.h"
#include "tests/support/test_data.h"

namespace dlslam::semantic {
namespace {

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Protobuf encoding, enough for the fields DeclaredInputSize reads.
std::string Varint(std::uint64_t v) {
  std::string out;
  do {
    out.push_back(static_cast<char>((v & 0x7f) | (v > 0x7f ? 0x80 : 0)));
    v >>= 7;
  } while (v != 0);
  return out;
}
std::string Field(std::uint32_t number, const std::string& message) {
  return Varint(number << 3 | 2) + Varint(message.size()) + message;
}
std::string IntField(std::uint32_t number, std::uint64_t value) { return Varint(number << 3) + Varint(value); }

// ValueInfoProto{name, type{tensor_type{elem_type 1, shape{dim...}}}}; a
// negative dimension is written symbolic (dim_param "d").
std::string Input(const std::string& name, const std::vector<int>& dims) {
  std::string shape;
  for (const int d : dims) shape += Field(1, d >= 0 ? IntField(1, static_cast<std::uint64_t>(d)) : Field(2, "d"));
  return Field(11, Field(1, name) + Field(2, Field(1, IntField(1, 1) + Field(2, shape))));
}
std::string Initializer(const std::string& name) {
  return Field(5, IntField(1, 4) + Field(8, name) + Field(9, std::string(64, '\x7f')));
}
std::string Model(const std::string& graph) {
  return IntField(1, 8) + Field(2, "test") + Field(7, graph) + Field(8, IntField(2, 11));
}

TEST(DeclaredInputSize, OfTheShippedModelAndTheFixtures) {
  const auto shipped = DeclaredInputSize(ReadAll(dlslam::testing::SourceDir() / "models" / kDefaultModelFile));
  ASSERT_TRUE(shipped.has_value());
  EXPECT_EQ(shipped->height, 209);
  EXPECT_EQ(shipped->width, 273);
  const auto fixture = DeclaredInputSize(ReadAll(dlslam::testing::FixturePath("semantic/identity_rgb.onnx")));
  ASSERT_TRUE(fixture.has_value());
  EXPECT_EQ(fixture->height, 209);
  EXPECT_EQ(fixture->width, 273);
}

TEST(DeclaredInputSize, OfATeacherExportedElsewhere) {
  DLSLAM_REQUIRE_SHARED_DATA(path, "models/deeplabv3-mnv2-voc/deeplabv3_mnv2_voc_385x513.onnx");
  const auto size = DeclaredInputSize(ReadAll(path));
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->height, 385);
  EXPECT_EQ(size->width, 513);
}

TEST(DeclaredInputSize, SkipsInitializersListedAsInputs) {
  const std::string graph = Initializer("weights") + Input("weights", {8, 3, 3, 3}) + Input("image", {1, 3, 65, 81});
  const auto size = DeclaredInputSize(Model(graph));
  ASSERT_TRUE(size.has_value());
  EXPECT_EQ(size->height, 65);
  EXPECT_EQ(size->width, 81);
}

TEST(DeclaredInputSize, NoneForSymbolicOrOtherShapes) {
  EXPECT_FALSE(DeclaredInputSize(Model(Input("x", {1, 3, -1, -1}))));
  EXPECT_FALSE(DeclaredInputSize(Model(Input("x", {1, 3, 65}))));
  EXPECT_FALSE(DeclaredInputSize(Model(Input("x", {1, 3, 0, 81}))));
  EXPECT_FALSE(DeclaredInputSize(Model(Input("x", {1, 3, 65, 81, 2}))));
  EXPECT_FALSE(DeclaredInputSize(Model(Initializer("w"))));  // no input at all
  EXPECT_FALSE(DeclaredInputSize(Model("")));
  EXPECT_FALSE(DeclaredInputSize(""));
  EXPECT_FALSE(DeclaredInputSize("this is not a model\n"));
  // A dimension beyond int: not a size.
  const std::string huge = Field(11, Field(1, "x") + Field(2, Field(1, Field(2, Field(1, IntField(1, 1)) +
                                                                              Field(1, IntField(1, 3)) +
                                                                              Field(1, IntField(1, 1ull << 40)) +
                                                                              Field(1, IntField(1, 81))))));
  EXPECT_FALSE(DeclaredInputSize(Model(huge)));
}

TEST(DeclaredInputSize, EveryTruncationAndCorruptionIsSafe) {
  const std::string graph = Initializer("w") + Input("image", {1, 3, 65, 81});
  const std::string model = Model(graph);
  const std::size_t graph_end = IntField(1, 8).size() + Field(2, "test").size() + Field(7, graph).size();
  for (std::size_t n = 0; n <= model.size(); ++n) {
    // Cut before the graph ends: malformed. After: the trailing opset field is cut, the graph is whole.
    const auto size = DeclaredInputSize(model.substr(0, n));
    EXPECT_EQ(size.has_value(), n >= graph_end) << n;
    if (size) {
      EXPECT_EQ(size->height, 65) << n;
    }
  }
  std::mt19937 rng(7);
  const std::string shipped = ReadAll(dlslam::testing::SourceDir() / "models" / kDefaultModelFile);
  ASSERT_GT(shipped.size(), 4096u);
  for (int trial = 0; trial < 300; ++trial) {
    std::string bytes = trial % 2 ? model : shipped.substr(0, 4096 + rng() % 60000);
    for (int flips = 0; flips < 1 + trial % 4; ++flips) {
      bytes[rng() % bytes.size()] = static_cast<char>(rng() & 0xff);
    }
    const auto size = DeclaredInputSize(bytes);  // must return, whatever it says
    if (size) {
      EXPECT_GT(size->height, 0);
      EXPECT_GT(size->width, 0);
    }
  }
  std::string noise(20000, '\0');
  for (int trial = 0; trial < 50; ++trial) {
    for (char& c : noise) c = static_cast<char>(rng() & 0xff);
    (void)DeclaredInputSize(noise);
  }
}

}  // namespace
}  // namespace dlslam::semantic
