#include "dlslam/io/camera_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "dlslam/io/settings.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;

class CameraSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = testing::MakeTempDir("camera_source");
    folder_ = root_ / "rgbd_dataset_freiburg1_xyz";
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  void Write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
  }
  CameraChoice Resolve(const CameraHints& hints = {}) {
    return ResolveCamera(folder_, hints, [this] {
      ++size_reads_;
      return fake_image_size_;
    });
  }
  std::filesystem::path root_, folder_;
  int size_reads_ = 0;
  cv::Size fake_image_size_{700, 500};
};

TEST_F(CameraSourceTest, FolderNameNamesThePreset) {
  EXPECT_EQ(PresetFromFolderName("/data/rgbd_dataset_freiburg3_walking_xyz"), "freiburg3");
  EXPECT_EQ(PresetFromFolderName("/data/rgbd_dataset_freiburg2_desk/"), "freiburg2");
  EXPECT_EQ(PresetFromFolderName("/data/RGBD_BONN_balloon"), "bonn");
  EXPECT_EQ(PresetFromFolderName("/data/my_sequence"), std::nullopt);
  const CameraChoice choice = Resolve();
  EXPECT_EQ(choice.camera.name, "freiburg1");
  EXPECT_THAT(choice.camera_source, HasSubstr("folder name"));
  EXPECT_EQ(size_reads_, 0);
}

TEST_F(CameraSourceTest, SourcesAreTriedInTheDocumentedOrder) {
  CameraIntrinsics own = CameraPreset("freiburg3");
  own.fx = 600.0;
  own.depth_factor = 2000.0;
  WriteCameraSettings(root_ / "explicit.yaml", own, 30.0);
  own.fx = 610.0;
  WriteCameraSettings(folder_ / kFolderSettingsName, own, 30.0);
  Write(folder_ / kIntrinsicsMatrixName, "585 0 320\n0 585 240\n0 0 1\n");

  CameraHints hints;
  hints.settings_file = root_ / "explicit.yaml";
  hints.preset = "fr2";
  EXPECT_EQ(Resolve(hints).camera.fx, 600.0);
  hints.settings_file.clear();
  EXPECT_EQ(Resolve(hints).camera.name, "freiburg2");
  EXPECT_EQ(Resolve().camera.fx, 610.0);
  std::filesystem::remove(folder_ / kFolderSettingsName);
  const CameraChoice from_matrix = Resolve();
  EXPECT_EQ(from_matrix.camera.fx, 585.0);
  EXPECT_EQ(from_matrix.camera.width, 700);  // from the (fake) first image
  EXPECT_EQ(size_reads_, 1);
  std::filesystem::remove(folder_ / kIntrinsicsMatrixName);
  EXPECT_EQ(Resolve().camera.name, "freiburg1");
}

TEST_F(CameraSourceTest, DepthFactorOrder) {
  CameraIntrinsics own = CameraPreset("freiburg3");
  own.depth_factor = 2000.0;
  WriteCameraSettings(folder_ / kFolderSettingsName, own, 30.0);
  CameraHints hints;
  hints.depth_factor_comment = 1000.0;
  hints.depth_list = folder_ / "depth.txt";
  hints.depth_factor = 4000.0;
  EXPECT_EQ(Resolve(hints).camera.depth_factor, 4000.0);
  hints.depth_factor = 0.0;
  EXPECT_EQ(Resolve(hints).camera.depth_factor, 2000.0);
  std::filesystem::remove(folder_ / kFolderSettingsName);
  const CameraChoice from_comment = Resolve(hints);
  EXPECT_EQ(from_comment.camera.depth_factor, 1000.0);
  EXPECT_THAT(from_comment.depth_factor_source, HasSubstr("depth.txt"));
  hints.depth_factor_comment.reset();
  EXPECT_EQ(Resolve(hints).camera.depth_factor, 5000.0);
}

TEST_F(CameraSourceTest, UnknownCameraSaysHowToGiveOne) {
  const auto plain = root_ / "my_recording";
  std::filesystem::create_directories(plain);
  try {
    ResolveCamera(plain, {}, [] { return cv::Size(640, 480); });
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("my_recording"));
    EXPECT_THAT(e.what(), HasSubstr("--camera"));
    EXPECT_THAT(e.what(), HasSubstr("--settings"));
  }
  CameraHints hints;
  hints.preset = "kinect9";
  EXPECT_THROW(Resolve(hints), InputError);
}

TEST_F(CameraSourceTest, ImagesSmallerThanThePrincipalPointAreRejected) {
  Write(folder_ / kIntrinsicsMatrixName, "585 0 320\n0 585 240\n0 0 1\n");
  fake_image_size_ = {320, 240};  // cx = 320 lies outside
  EXPECT_THROW(Resolve(), InputError);
}

TEST_F(CameraSourceTest, IntrinsicsMatrixErrors) {
  Write(root_ / "two_rows.txt", "585 0 320\n0 585 240\n");
  EXPECT_THROW(ReadIntrinsicsMatrix(root_ / "two_rows.txt"), InputError);
  Write(root_ / "text.txt", "585 0 320\n0 f 240\n0 0 1\n");
  EXPECT_THROW(ReadIntrinsicsMatrix(root_ / "text.txt"), InputError);
  Write(root_ / "skew.txt", "585 3 320\n0 585 240\n0 0 1\n");
  EXPECT_THROW(ReadIntrinsicsMatrix(root_ / "skew.txt"), InputError);
}

TEST(ReadIntrinsicsMatrix, ReadsSevenScenesFile) {
  DLSLAM_REQUIRE_SHARED_DATA(path, "7scenes-redkitchen-500/camera-intrinsics.txt");
  const CameraIntrinsics c = ReadIntrinsicsMatrix(path);
  // Values stated in the shared data README: fx = fy = 585, cx = 320, cy = 240.
  EXPECT_EQ(c.fx, 585.0);
  EXPECT_EQ(c.fy, 585.0);
  EXPECT_EQ(c.cx, 320.0);
  EXPECT_EQ(c.cy, 240.0);
  EXPECT_FALSE(c.HasDistortion());
}

}  // namespace
}  // namespace dlslam::io
