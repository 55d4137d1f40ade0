#include "dlslam/io/sequence.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/imgcodecs.hpp>

#include "dlslam/io/sequence_test_folder.h"
#include "dlslam/util/check.h"
#include "tests/support/test_data.h"

namespace dlslam::io {
namespace {

using ::testing::HasSubstr;
using testing::SequenceFolder;

// Median of the valid (> 0) depths [m] and the valid fraction.
std::pair<double, double> DepthStats(const cv::Mat& depth) {
  std::vector<float> valid;
  for (int r = 0; r < depth.rows; ++r) {
    for (int c = 0; c < depth.cols; ++c) {
      if (depth.at<float>(r, c) > 0) valid.push_back(depth.at<float>(r, c));
    }
  }
  if (valid.empty()) return {0.0, 0.0};
  std::nth_element(valid.begin(), valid.begin() + static_cast<long>(valid.size() / 2), valid.end());
  return {valid[valid.size() / 2],
          static_cast<double>(valid.size()) / static_cast<double>(depth.total())};
}

TEST(RgbdSequence, ReadsAConstructedSequence) {
  SequenceFolder folder;
  folder.WriteValidSequence(4);
  folder.WriteText("groundtruth.txt", "# gt\n1000.0 0 0 0 0 0 0 1\n1000.1 0.1 0 0 0 0 0 1\n");
  folder.WriteText("accelerometer.txt", "1000.0 0.0 9.81 0.0\n");
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  ASSERT_EQ(seq.size(), 4u);
  EXPECT_EQ(seq.camera().width, 64);
  EXPECT_THAT(seq.camera_source(), HasSubstr("camera.yaml"));
  EXPECT_DOUBLE_EQ(seq.camera().depth_factor, 5000.0);
  EXPECT_EQ(seq.frames()[2].rgb.path, "rgb/2.png");
  EXPECT_EQ(seq.frames()[2].rgb.line, 5);
  EXPECT_EQ(seq.frames()[2].depth.list_file, folder.dir() / "depth.txt");
  ASSERT_TRUE(seq.ground_truth().has_value());
  EXPECT_EQ(seq.ground_truth()->size(), 2u);
  EXPECT_EQ(seq.accelerometer().size(), 1u);
  EXPECT_EQ(seq.fps(), 30.0);

  const RgbdFrame frame = seq.LoadFrame(3);
  EXPECT_EQ(frame.index, 3u);
  EXPECT_DOUBLE_EQ(frame.timestamp, seq.frames()[3].rgb.timestamp);
  EXPECT_EQ(frame.color.type(), CV_8UC3);
  EXPECT_EQ(frame.depth.type(), CV_32FC1);
  EXPECT_EQ(frame.depth.size(), cv::Size(64, 48));
  EXPECT_FLOAT_EQ(frame.depth.at<float>(10, 10), 5030.0f / 5000.0f);
  EXPECT_EQ(frame.depth.at<float>(0, 0), 0.0f);
  EXPECT_TRUE(seq.TryLoadFrame(0).ok());
  EXPECT_THROW(seq.LoadFrame(4), Error);
}

TEST(RgbdSequence, WithoutMaskListFramesHaveNoMask) {
  SequenceFolder folder;
  folder.WriteValidSequence(2);
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  EXPECT_FALSE(seq.has_masks());
  EXPECT_TRUE(seq.LoadFrame(0).mask.empty());
}

TEST(RgbdSequence, LoadsMasksAssociatedByTime) {
  SequenceFolder folder;
  folder.WriteValidSequence(4);
  folder.WriteMasks(4, {64, 48}, 129);
  // Frame 2's mask is listed 30 ms late: beyond the 20 ms association limit.
  folder.WriteText("mask.txt",
                   "# masks\n1000.000000 mask/0.png\n1000.043333 mask/1.png\n1000.096667 mask/2.png\n"
                   "1000.100000 mask/3.png\n");
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  EXPECT_TRUE(seq.has_masks());
  EXPECT_EQ(seq.frames_with_mask(), 3u);
  EXPECT_EQ(seq.mask_list().size(), 4u);
  ASSERT_TRUE(seq.frames()[1].mask.has_value());
  EXPECT_EQ(seq.frames()[1].mask->path, "mask/1.png");
  EXPECT_FALSE(seq.frames()[2].mask.has_value());
  const RgbdFrame frame = seq.LoadFrame(1);
  ASSERT_EQ(frame.mask.type(), CV_8UC1);
  EXPECT_EQ(frame.mask.size(), cv::Size(64, 48));
  EXPECT_EQ(frame.mask.at<uchar>(5, 7), 129);
  EXPECT_TRUE(seq.LoadFrame(2).mask.empty());
}

TEST(RgbdSequence, UnmatchedImagesAreLeftOutAndCounted) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  // A depth image 25 ms after frame 1's colour: beyond 0.02 s, so frame 1 has
  // no depth; an extra colour image with no depth at all.
  folder.WriteText("depth.txt",
                   "1000.002 depth/0.png\n1000.058333 depth/1.png\n1000.068667 depth/2.png\n");
  folder.WriteText(
      "rgb.txt",
      "1000.0 rgb/0.png\n1000.033333 rgb/1.png\n1000.066667 rgb/2.png\n1005.0 rgb/2.png\n");
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  EXPECT_EQ(seq.rgb_list().size(), 4u);
  EXPECT_EQ(seq.depth_list().size(), 3u);
  ASSERT_EQ(seq.size(), 2u);
  EXPECT_EQ(seq.frames()[0].depth.path, "depth/0.png");
  EXPECT_EQ(seq.frames()[1].rgb.path, "rgb/2.png");
  EXPECT_EQ(seq.frames()[1].depth.path, "depth/2.png");
  RgbdSequenceOptions wide;
  wide.max_association_diff = 0.03;
  EXPECT_EQ(RgbdSequence::Open(folder.dir(), wide).size(), 3u);
}

TEST(RgbdSequence, AssociationFileReplacesTheLists) {
  SequenceFolder folder;
  folder.WriteValidSequence(3);
  const auto assoc = folder.root() / "pairs.txt";
  std::ofstream(assoc) << "1000.033333 rgb/1.png 1000.035333 depth/1.png\n"
                          "1000.066667 rgb/2.png 1000.068667 depth/0.png\n";
  RgbdSequenceOptions options;
  options.associations_file = assoc;
  const RgbdSequence seq = RgbdSequence::Open(folder.dir(), options);
  ASSERT_EQ(seq.size(), 2u);
  EXPECT_TRUE(seq.rgb_list().empty());
  EXPECT_EQ(seq.frames()[1].depth.path, "depth/0.png");
  EXPECT_EQ(seq.frames()[1].depth.list_file, assoc);
  EXPECT_FLOAT_EQ(seq.LoadFrame(1).depth.at<float>(5, 5), 1.0f);
}

// 3 real fr3/walking_xyz colour frames, 2 with depth (shared data README).
TEST(RgbdSequence, ReadsRealTumFrames) {
  DLSLAM_REQUIRE_SHARED_DATA(sample, "real-samples/tum_walking_xyz_3frames");
  SequenceFolder folder("rgbd_dataset_freiburg3_walking_xyz");
  std::string rgb = "# color images\n", depth = "# depth maps\n";
  for (const auto& entry : std::filesystem::directory_iterator(sample / "rgb")) {
    std::filesystem::create_symlink(entry.path(), folder.dir() / "rgb" / entry.path().filename());
  }
  for (const auto& entry : std::filesystem::directory_iterator(sample / "depth")) {
    std::filesystem::create_symlink(entry.path(), folder.dir() / "depth" / entry.path().filename());
  }
  folder.WriteText("rgb.txt", rgb +
                                  "1341846313.592026 rgb/1341846313.592026.png\n"
                                  "1341846316.570121 rgb/1341846316.570121.png\n"
                                  "1341846325.417931 rgb/1341846325.417931.png\n");
  folder.WriteText("depth.txt", depth +
                                    "1341846313.592088 depth/1341846313.592088.png\n"
                                    "1341846316.570146 depth/1341846316.570146.png\n");
  const RgbdSequence seq = RgbdSequence::Open(folder.dir());
  EXPECT_EQ(seq.camera().name, "freiburg3");
  EXPECT_THAT(seq.camera_source(), HasSubstr("folder name"));
  EXPECT_DOUBLE_EQ(seq.camera().depth_factor, 5000.0);
  ASSERT_EQ(seq.size(), 2u);
  EXPECT_EQ(seq.frames()[0].depth.path, "depth/1341846313.592088.png");
  EXPECT_EQ(seq.frames()[1].depth.path, "depth/1341846316.570146.png");

  const RgbdFrame frame = seq.LoadFrame(0);
  EXPECT_EQ(frame.color.size(), cv::Size(640, 480));
  const cv::Mat raw =
      cv::imread((sample / "depth/1341846313.592088.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  EXPECT_FLOAT_EQ(frame.depth.at<float>(240, 320), raw.at<uint16_t>(240, 320) / 5000.0f);
  const auto [median, valid] = DepthStats(frame.depth);
  // An office seen from a person's height: metres, not millimetres or km.
  EXPECT_GT(median, 0.5);
  EXPECT_LT(median, 5.0);
  EXPECT_GT(valid, 0.5);
}

TEST(RgbdSequence, ReadsSevenScenesWithMillimetreDepth) {
  DLSLAM_REQUIRE_SHARED_DATA(dir, "7scenes-redkitchen-500");
  const RgbdSequence seq = RgbdSequence::Open(dir);
  EXPECT_EQ(seq.size(), 500u);
  EXPECT_THAT(seq.camera_source(), HasSubstr("camera-intrinsics.txt"));
  EXPECT_EQ(seq.camera().fx, 585.0);
  EXPECT_EQ(seq.camera().width, 640);
  EXPECT_DOUBLE_EQ(seq.camera().depth_factor, 1000.0);
  EXPECT_THAT(seq.depth_factor_source(), HasSubstr("depth.txt"));
  ASSERT_TRUE(seq.ground_truth().has_value());
  EXPECT_EQ(seq.ground_truth()->size(), 500u);

  const RgbdFrame frame = seq.LoadFrame(0);
  EXPECT_EQ(frame.color.type(), CV_8UC3);  // from JPEG
  const auto [median, valid] = DepthStats(frame.depth);
  // A kitchen counter seen from a hand-held Kinect: about a metre or two.
  EXPECT_GT(median, 0.4);
  EXPECT_LT(median, 4.0);
  EXPECT_GT(valid, 0.3);

  RgbdSequenceOptions options;
  options.associations_file = dir / "associations.txt";
  const RgbdSequence from_pairs = RgbdSequence::Open(dir, options);
  ASSERT_EQ(from_pairs.size(), seq.size());
  for (std::size_t i = 0; i < seq.size(); ++i) {
    ASSERT_EQ(from_pairs.frames()[i].depth.path, seq.frames()[i].depth.path) << i;
  }
  EXPECT_DOUBLE_EQ(from_pairs.camera().depth_factor, 1000.0);
}

}  // namespace
}  // namespace dlslam::io
