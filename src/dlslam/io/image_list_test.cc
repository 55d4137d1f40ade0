#include "dlslam/io/image_list.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/io/accelerometer.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;

class ImageListTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("image_list"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  template <typename F>
  static std::string ErrorOf(F&& read) {
    try {
      read();
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no error>";
  }
  std::filesystem::path dir_;
};

TEST_F(ImageListTest, ReadsTumListWithCommentsAndLineNumbers) {
  const auto path = Write("rgb.txt",
                          "# color images\n# file: 'x.bag'\n# timestamp filename\n"
                          "1305031102.175304 rgb/1305031102.175304.png\n\n"
                          "1305031102.211214\trgb/1305031102.211214.png\r\n");
  const ImageList list = ReadImageList(path);
  ASSERT_EQ(list.images.size(), 2u);
  EXPECT_EQ(list.comments.size(), 3u);
  EXPECT_DOUBLE_EQ(list.images[0].timestamp, 1305031102.175304);
  EXPECT_EQ(list.images[1].path, "rgb/1305031102.211214.png");
  EXPECT_EQ(list.images[0].line, 4);
  EXPECT_EQ(list.images[1].line, 6);
  EXPECT_EQ(list.images[1].list_file, path);
}

TEST_F(ImageListTest, BadListsNameFileAndLine) {
  const auto malformed = Write("a.txt", "# c\n1.0 rgb/1.png\n2.0 rgb/2.png extra\n");
  EXPECT_THAT(ErrorOf([&] { ReadImageList(malformed); }),
              HasSubstr("a.txt:3: expected 'timestamp path', got 3 fields"));
  const auto not_number = Write("b.txt", "1.0 rgb/1.png\n1.0x rgb/2.png\n");
  EXPECT_THAT(ErrorOf([&] { ReadImageList(not_number); }),
              HasSubstr("b.txt:2: image timestamp '1.0x'"));
  const auto backwards = Write("c.txt", "1.0 rgb/1.png\n2.0 rgb/2.png\n1.5 rgb/3.png\n");
  EXPECT_THAT(ErrorOf([&] { ReadImageList(backwards); }),
              HasSubstr("c.txt:3: image timestamp 1.500000"));
  const auto duplicate = Write("d.txt", "1.0 rgb/1.png\n1.0 rgb/2.png\n");
  EXPECT_THAT(ErrorOf([&] { ReadImageList(duplicate); }), HasSubstr("d.txt:2:"));
  EXPECT_THAT(ErrorOf([&] { ReadImageList(dir_ / "missing.txt"); }), HasSubstr("file not found"));
}

TEST_F(ImageListTest, ReadsAssociationFilesAndRejectsBadOnes) {
  const auto good =
      Write("assoc.txt", "1.0 rgb/1.png 1.01 depth/1.png\n2.0 rgb/2.png 1.99 depth/2.png\n");
  const auto pairs = ReadAssociationFile(good);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_DOUBLE_EQ(pairs[1].depth.timestamp, 1.99);
  EXPECT_EQ(pairs[1].depth.path, "depth/2.png");
  EXPECT_EQ(pairs[1].rgb.line, 2);
  const auto three = Write("bad.txt", "1.0 rgb/1.png 1.01\n");
  EXPECT_THAT(ErrorOf([&] { ReadAssociationFile(three); }),
              HasSubstr("bad.txt:1: expected 't_rgb"));
  const auto depth_nan = Write("nan.txt", "1.0 rgb/1.png nan depth/1.png\n");
  EXPECT_THAT(ErrorOf([&] { ReadAssociationFile(depth_nan); }),
              HasSubstr("nan.txt:1: depth timestamp"));
}

TEST_F(ImageListTest, ReadsRealAssociationFiles) {
  DLSLAM_REQUIRE_SHARED_DATA(path, "tum/associations/rgbd_dataset_freiburg3_walking_xyz.txt");
  const auto pairs = ReadAssociationFile(path);
  // The shared data README gives 827 pairs for walking_xyz.
  ASSERT_EQ(pairs.size(), 827u);
  EXPECT_DOUBLE_EQ(pairs[0].rgb.timestamp, 1341846313.592026);
  EXPECT_EQ(pairs[0].depth.path, "depth/1341846313.592088.png");
}

TEST(DepthFactorFromComments, FindsTheCommonSpellings) {
  EXPECT_EQ(DepthFactorFromComments({" 16-bit PNG, millimetres (depth factor 1000, NOT TUM 5000)"}),
            1000.0);
  EXPECT_EQ(DepthFactorFromComments({"depth_factor: 5000"}), 5000.0);
  EXPECT_EQ(DepthFactorFromComments({"x", "DepthMapFactor = 1000.5"}), 1000.5);
  EXPECT_EQ(DepthFactorFromComments({" depth maps", " timestamp filename"}), std::nullopt);
  EXPECT_EQ(DepthFactorFromComments({"depth factor 0"}), std::nullopt);
}

TEST_F(ImageListTest, ReadsAccelerometerAndRejectsBadLines) {
  const auto good = Write("accelerometer.txt",
                          "# accelerometer data\n# timestamp ax ay az\n"
                          "1305031102.1 -0.0794 9.6529 0.6845\n1305031102.2 -0.08 9.65 0.68\n");
  const auto samples = ReadAccelerometer(good);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_DOUBLE_EQ(samples[0].acceleration.y(), 9.6529);
  const auto short_line = Write("a2.txt", "1.0 0 9.8\n");
  EXPECT_THAT(ErrorOf([&] { ReadAccelerometer(short_line); }), HasSubstr("a2.txt:1: expected"));
  const auto backwards = Write("a3.txt", "2.0 0 9.8 0\n1.0 0 9.8 0\n");
  EXPECT_THAT(ErrorOf([&] { ReadAccelerometer(backwards); }), HasSubstr("a3.txt:2: timestamp"));
}

}  // namespace
}  // namespace dlslam::io
