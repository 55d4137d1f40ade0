#include "dlslam/io/file_util.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class ReadFileBytesTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = dlslam::testing::MakeTempDir("file_util"); }
  void TearDown() override { fs::remove_all(dir_); }
  // The InputError message for reading `path` (which it must name).
  static std::string Error(const fs::path& path) {
    try {
      ReadFileBytes(path, "model");
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      return e.what();
    }
    ADD_FAILURE() << "no error for " << path;
    return {};
  }
  fs::path dir_;
};

TEST_F(ReadFileBytesTest, ReadsEveryByte) {
  const std::string content("a\0b\nc\r\n\xff", 8);
  std::ofstream(dir_ / "f.bin", std::ios::binary) << content;
  const std::vector<unsigned char> bytes = ReadFileBytes(dir_ / "f.bin", "model");
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), content);
}

TEST_F(ReadFileBytesTest, NamesTheFileAndTheProblem) {
  EXPECT_THAT(Error(dir_ / "missing.onnx"), HasSubstr("model file not found"));
  EXPECT_THAT(Error(dir_), HasSubstr("is a directory"));
  std::ofstream(dir_ / "empty.onnx").close();
  EXPECT_THAT(Error(dir_ / "empty.onnx"), HasSubstr("empty"));
}

}  // namespace
}  // namespace dlslam::io
