#include "dlslam/io/frame_prefetcher.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "dlslam/io/sequence_test_folder.h"

namespace dlslam::io {
namespace {

TEST(FramePrefetcher, DeliversEveryFrameInOrderWithBadImagesAsTheirFramesErrors) {
  testing::SequenceFolder folder;
  folder.WriteValidSequence(7);
  std::filesystem::remove(folder.dir() / "depth/3.png");
  folder.WriteText("rgb/5.png", "not an image");
  const RgbdSequence sequence = RgbdSequence::Open(folder.dir());
  ASSERT_EQ(sequence.size(), 7u);

  FramePrefetcher frames(sequence, sequence.size(), /*ahead=*/1);
  std::size_t expected = 0;
  while (std::optional<FramePrefetcher::Item> item = frames.Next()) {
    EXPECT_EQ(item->index, expected);
    const FrameLoadResult direct = sequence.TryLoadFrame(expected);
    ASSERT_EQ(item->result.ok(), direct.ok()) << "frame " << expected;
    EXPECT_EQ(item->result.error, direct.error);
    if (direct.ok()) {
      EXPECT_EQ(item->result.frame->timestamp, direct.frame->timestamp);
      EXPECT_EQ(cv::norm(item->result.frame->color, direct.frame->color, cv::NORM_INF), 0.0);
      EXPECT_EQ(cv::norm(item->result.frame->depth, direct.frame->depth, cv::NORM_INF), 0.0);
    } else {
      EXPECT_TRUE(expected == 3 || expected == 5) << item->result.error;
    }
    ++expected;
  }
  EXPECT_EQ(expected, 7u);
  EXPECT_FALSE(frames.Next().has_value());  // stays at the end
}

TEST(FramePrefetcher, StopsEarlyWhenDestroyedAndReadsOnlyTheFramesAsked) {
  testing::SequenceFolder folder;
  folder.WriteValidSequence(6);
  const RgbdSequence sequence = RgbdSequence::Open(folder.dir());
  {
    FramePrefetcher frames(sequence, 4);
    std::size_t n = 0;
    while (frames.Next()) ++n;
    EXPECT_EQ(n, 4u);
  }
  {
    FramePrefetcher frames(sequence, sequence.size(), 2);
    ASSERT_TRUE(frames.Next().has_value());
  }  // destroyed with frames still to read: joins without hanging
  EXPECT_THROW(FramePrefetcher(sequence, 7), Error);
  EXPECT_THROW(FramePrefetcher(sequence, 4, 2, 20), Error);  // nice beyond Linux's 19
  EXPECT_THROW(FramePrefetcher(sequence, 4, 2, -1), Error);  // raising priority is not offered
  FramePrefetcher unlowered(sequence, 4, 2, 0);
  EXPECT_TRUE(unlowered.Next().has_value());
}

}  // namespace
}  // namespace dlslam::io
