#include "dlslam/io/sequence_writer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <fstream>

#include "dlslam/io/text_table.h"
#include "dlslam/io/trajectory_io.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class SequenceWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("sequence_writer");
    camera_ = CameraPreset("freiburg3");
  }
  void TearDown() override { fs::remove_all(dir_); }

  struct Frame {
    double t;
    cv::Mat colour, depth, mask;
    SE3d pose;
  };
  Frame MakeFrame(int i) const {
    Frame f;
    f.t = 1700000000.0 + i / 30.0;
    f.colour = cv::Mat(480, 640, CV_8UC3);
    cv::randu(f.colour, 0, 256);
    f.depth = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.2345f + 0.1f * i));
    f.depth(cv::Rect(0, 0, 10, 10)).setTo(0.0f);  // holes
    f.depth.at<float>(20, 20) = 20.0f;              // beyond the 16-bit range
    f.mask = cv::Mat(480, 640, CV_8UC1, cv::Scalar(0));
    f.mask(cv::Rect(100, 100, 50, 80)).setTo(1 + 128);
    f.mask(cv::Rect(300, 200, 20, 20)).setTo(2);
    f.pose = SE3d(SO3d::Exp(Eigen::Vector3d(0.1 * i, -0.2, 0.3)), Eigen::Vector3d(i, 2.0, -1.5));
    return f;
  }
  std::vector<Frame> WriteFrames(const fs::path& dir, int n, bool force = false) {
    SequenceWriterOptions options;
    options.description = "dlslam synth test";
    options.force = force;
    SequenceWriter writer(dir, camera_, options);
    std::vector<Frame> frames;
    for (int i = 0; i < n; ++i) {
      frames.push_back(MakeFrame(i));
      writer.Add(frames.back().t, frames.back().colour, frames.back().depth, frames.back().mask, frames.back().pose);
    }
    writer.Finish();
    return frames;
  }
  std::string ErrorOf(const fs::path& dir, bool force = false) {
    try {
      WriteFrames(dir, 1, force);
    } catch (const InputError& e) {
      return e.what();
    }
    return "<no error>";
  }

  fs::path dir_;
  CameraIntrinsics camera_;
};

TEST_F(SequenceWriterTest, WritesTheTumLayoutThatReadsBack) {
  const fs::path out = dir_ / "seq";
  const auto frames = WriteFrames(out, 3);
  const TextTable rgb = ReadTextTable(out / "rgb.txt");
  ASSERT_EQ(rgb.rows.size(), 3u);
  EXPECT_THAT(rgb.comments.front(), HasSubstr("color images"));
  EXPECT_EQ(rgb.rows[1].fields, (std::vector<std::string>{"1700000000.033333", "rgb/1700000000.033333.png"}));
  const TextTable depth = ReadTextTable(out / "depth.txt");
  ASSERT_EQ(depth.rows.size(), 3u);
  EXPECT_EQ(depth.rows[2].fields[1], "depth/1700000000.066667.png");
  const TextTable mask = ReadTextTable(out / "mask.txt");
  ASSERT_EQ(mask.rows.size(), 3u);
  EXPECT_EQ(mask.rows[0].fields[1], "mask/1700000000.000000.png");
  const TextTable assoc = ReadTextTable(out / "associations.txt");
  ASSERT_EQ(assoc.rows.size(), 3u);
  EXPECT_EQ(assoc.rows[0].fields.size(), 4u);

  const Trajectory gt = ReadTumTrajectory(out / "groundtruth.txt");
  ASSERT_EQ(gt.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(gt[i].timestamp, std::stod(rgb.rows[i].fields[0]));
    EXPECT_LT((gt[i].translation - frames[i].pose.translation()).norm(), 1e-12);
    EXPECT_LT(gt[i].world_from_cam().so3().Log().norm() - frames[i].pose.so3().Log().norm(), 1e-12);
  }

  for (std::size_t i = 0; i < 3; ++i) {
    const std::string t = rgb.rows[i].fields[0];
    const cv::Mat colour = cv::imread((out / "rgb" / (t + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(colour.type(), CV_8UC3);
    EXPECT_EQ(cv::norm(colour, frames[i].colour, cv::NORM_INF), 0);
    const cv::Mat raw = cv::imread((out / "depth" / (t + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(raw.type(), CV_16UC1);
    EXPECT_EQ(raw.at<std::uint16_t>(5, 5), 0) << "hole";
    EXPECT_EQ(raw.at<std::uint16_t>(20, 20), 65535) << "clamped";
    EXPECT_EQ(raw.at<std::uint16_t>(300, 300), static_cast<int>(std::lround((1.2345f + 0.1f * i) * 5000)));
    const cv::Mat m = cv::imread((out / "mask" / (t + ".png")).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(m.type(), CV_8UC1);
    EXPECT_EQ(cv::norm(m, frames[i].mask, cv::NORM_INF), 0);
  }

  cv::FileStorage yaml((out / "camera.yaml").string(), cv::FileStorage::READ);
  ASSERT_TRUE(yaml.isOpened());
  EXPECT_DOUBLE_EQ(yaml["Camera.fx"].real(), 535.4);
  EXPECT_DOUBLE_EQ(yaml["Camera.cy"].real(), 247.6);
  EXPECT_DOUBLE_EQ(yaml["Camera.k1"].real(), 0.0);
  EXPECT_EQ(static_cast<int>(yaml["Camera.width"]), 640);
  EXPECT_EQ(static_cast<int>(yaml["Camera.height"]), 480);
  EXPECT_DOUBLE_EQ(yaml["Camera.fps"].real(), 30.0);
  EXPECT_DOUBLE_EQ(yaml["Camera.bf"].real(), 40.0);
  EXPECT_DOUBLE_EQ(yaml["DepthMapFactor"].real(), 5000.0);
  EXPECT_TRUE(yaml["Camera.fps"].isReal()) << "written as a real, as ORB-SLAM reads it";
}

TEST_F(SequenceWriterTest, RefusesForeignFoldersAndNeverDeletesUserFiles) {
  const fs::path foreign = dir_ / "mine";
  fs::create_directories(foreign);
  std::ofstream(foreign / "notes.txt") << "precious";
  EXPECT_THAT(ErrorOf(foreign), HasSubstr("is not empty and was not written by dlslam synth"));
  EXPECT_TRUE(fs::is_empty(foreign / "notes.txt") == false);
  EXPECT_FALSE(fs::exists(foreign / "rgb"));
  // --force writes beside the user's file and keeps it.
  EXPECT_EQ(ErrorOf(foreign, true), "<no error>");
  EXPECT_TRUE(fs::exists(foreign / "notes.txt"));
  EXPECT_TRUE(fs::exists(foreign / "rgb.txt"));

  std::ofstream(dir_ / "file") << "x";
  EXPECT_THAT(ErrorOf(dir_ / "file"), HasSubstr("exists and is not a directory"));
  EXPECT_EQ(ErrorOf(dir_ / "empty_is_fine"), "<no error>");
}

TEST_F(SequenceWriterTest, RewritingOurFolderReplacesTheEarlierFramesOnly) {
  const fs::path out = dir_ / "seq";
  WriteFrames(out, 3);
  std::ofstream(out / "rgb" / "my_edit.png") << "not ours";
  std::ofstream(out / "README") << "user notes";
  WriteFrames(out, 1);
  EXPECT_EQ(ReadTextTable(out / "rgb.txt").rows.size(), 1u);
  EXPECT_FALSE(fs::exists(out / "rgb" / "1700000000.033333.png")) << "stale frame removed";
  EXPECT_FALSE(fs::exists(out / "depth" / "1700000000.066667.png"));
  EXPECT_TRUE(fs::exists(out / "rgb" / "1700000000.000000.png"));
  EXPECT_TRUE(fs::exists(out / "rgb" / "my_edit.png")) << "not named like our frames";
  EXPECT_TRUE(fs::exists(out / "README"));
}

TEST_F(SequenceWriterTest, RejectsBadFrames) {
  SequenceWriter writer(dir_ / "seq", camera_, {});
  const Frame f = MakeFrame(0);
  EXPECT_THROW(writer.Add(f.t, cv::Mat(10, 10, CV_8UC3), f.depth, f.mask, f.pose), Error);
  cv::Mat depth16;
  f.depth.convertTo(depth16, CV_16U);
  EXPECT_THROW(writer.Add(f.t, f.colour, depth16, f.mask, f.pose), Error);
  writer.Add(f.t, f.colour, f.depth, f.mask, f.pose);
  EXPECT_THROW(writer.Add(f.t, f.colour, f.depth, f.mask, f.pose), Error) << "timestamps must increase";
  EXPECT_THROW(writer.Add(f.t + 1, f.colour, f.depth, cv::Mat(), f.pose), Error) << "masks for all or none";
}

TEST(DepthToRaw16, RoundsAndKeepsHoles) {
  cv::Mat z(1, 5, CV_32FC1);
  z.at<float>(0, 0) = 0.0f;
  z.at<float>(0, 1) = 1.00009f;
  z.at<float>(0, 2) = std::numeric_limits<float>::quiet_NaN();
  z.at<float>(0, 3) = -1.0f;
  z.at<float>(0, 4) = 13.107f;
  const cv::Mat raw = DepthToRaw16(z, 5000.0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 0), 0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 1), 5000);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 2), 0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 3), 0);
  EXPECT_EQ(raw.at<std::uint16_t>(0, 4), 65535);
}

}  // namespace
}  // namespace dlslam::io
