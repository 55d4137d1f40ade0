#include "dlslam/system/semantic_feed.h"

#include <gtest/gtest.h>

#include "dlslam/semantic/label_maps.h"
#include "dlslam/util/check.h"

namespace dlslam {
namespace {

// A stand-in network: the frame's blue value is its id, and the "person" a
// 10 x 10 square at x = id, so each mask tells which image it was made on.
class IdSegmenter : public semantic::Segmenter {
 public:
  IdSegmenter() { options_.dynamic_margin_px = 0; }
  semantic::SegmentationResult Segment(const cv::Mat& bgr) override {
    const int id = bgr.at<cv::Vec3b>(0, 0)[0];
    cv::Mat labels(bgr.size(), CV_8UC1, cv::Scalar(0));
    labels(cv::Rect(id, 10, 10, 10)).setTo(1);
    return semantic::ResultFromLabels(labels, bgr.size(), options_);
  }
  const semantic::SegmenterOptions& options() const override { return options_; }

 private:
  semantic::SegmenterOptions options_;
};

cv::Mat Image(int id) { return cv::Mat(40, 80, CV_8UC3, cv::Scalar(id, 0, 0)); }

// The id of the image a mask was made on: the left edge of its square (-1: no square).
int MadeOn(const cv::Mat& mask) {
  if (mask.empty()) return -1;
  for (int x = 0; x < mask.cols; ++x) {
    if (mask.at<uchar>(15, x) != 0) return x;
  }
  return -1;
}

CameraIntrinsics SmallCamera() {
  CameraIntrinsics camera;
  camera.width = 80;
  camera.height = 40;
  camera.cx = 39.5;
  camera.cy = 19.5;
  camera.fx = camera.fy = 60.0;
  return camera;
}

struct Feed {
  explicit Feed(bool wait_for_masks, int carried_segment_every = 1) {
    SemanticThreadOptions options;
    options.wait_for_masks = wait_for_masks;
    options.carried_segment_every = carried_segment_every;
    feed = std::make_unique<SemanticFeed>(options, SmallCamera(), &timings, [] { return std::optional<SE3d>(); },
                                          std::make_unique<IdSegmenter>());
  }
  StageTimings timings;
  std::unique_ptr<SemanticFeed> feed;
};

TEST(SemanticFeed, WaitingFramesGetTheirOwnMasksOrThoseSegmentedAhead) {
  Feed f(/*wait_for_masks=*/true);
  EXPECT_FALSE(f.feed->asynchronous());
  f.feed->SegmentAhead(Image(5), 1.0);
  f.feed->SegmentAhead(Image(6), 2.0);
  f.feed->SegmentAhead(Image(7), 3.0);  // a third frame ahead: not segmented
  // t = 1 was never tracked: dropped; t = 2 takes what was segmented ahead for it.
  SemanticFeed::FrameMasks m = f.feed->ForFrame(1, Image(6), cv::Mat(), 2.0, /*carry=*/false);
  EXPECT_TRUE(m.segmented_ahead);
  EXPECT_FALSE(m.carried);
  EXPECT_EQ(MadeOn(m.prior().dynamic), 6);
  m = f.feed->ForFrame(2, Image(9), cv::Mat(), 3.0, /*carry=*/false);
  EXPECT_FALSE(m.segmented_ahead);
  EXPECT_EQ(MadeOn(m.prior().dynamic), 9);
  // Out of frame order: not segmented ahead.
  f.feed->SegmentAhead(Image(20), 5.0);
  f.feed->SegmentAhead(Image(21), 4.0);
  m = f.feed->ForFrame(3, Image(22), cv::Mat(), 4.0, /*carry=*/false);
  EXPECT_FALSE(m.segmented_ahead);
  EXPECT_EQ(MadeOn(m.prior().dynamic), 22);
  EXPECT_TRUE(f.feed->ForFrame(4, Image(20), cv::Mat(), 5.0, false).segmented_ahead);
  EXPECT_THROW(f.feed->ForFrame(5, Image(1), cv::Mat(), 6.0, /*carry=*/true), Error);
  EXPECT_EQ(f.timings.Summaries().at("semantic").count, 3u);  // timed when the dynamic stage took them
  f.feed->Stop();
}

TEST(SemanticFeed, CarriedFramesGetTheNewestFinishedMasks) {
  // The network takes a carried frame only 2 frames after the last one it
  // took: frame 2 stays out, so frame 1's masks are the newest for certain
  // (with every frame, frame 2's could finish first: a race, failing 1 run in 6).
  Feed f(/*wait_for_masks=*/false, /*carried_segment_every=*/2);
  ASSERT_TRUE(f.feed->asynchronous());
  f.feed->SegmentAhead(Image(5), 1.0);  // kept, segmented only after a frame that waits
  SemanticFeed::FrameMasks first = f.feed->ForFrame(1, Image(12), cv::Mat(), 1.0, /*carry=*/true);
  EXPECT_TRUE(first.carried);
  EXPECT_FALSE(first.segmented_ahead);
  ASSERT_TRUE(first.own.has_value());  // the network was free
  first.own->wait();
  // The next frame carries frame 1's masks (no pose: in place, grown).
  SemanticFeed::FrameMasks next = f.feed->ForFrame(2, Image(30), cv::Mat(), 2.0, /*carry=*/true);
  EXPECT_FALSE(next.own.has_value());
  const dynamic::SemanticMasks carried = next.prior();
  ASSERT_FALSE(carried.dynamic.empty());
  EXPECT_NE(carried.dynamic.at<uchar>(15, 16), 0);  // frame 1's square
  EXPECT_EQ(carried.dynamic.at<uchar>(15, 75), 0);  // far from it
  // Not carried (a crowded view): its own masks, waited for.
  const SemanticFeed::FrameMasks own = f.feed->ForFrame(3, Image(40), cv::Mat(), 3.0, /*carry=*/false);
  EXPECT_FALSE(own.carried);
  EXPECT_EQ(MadeOn(own.prior().dynamic), 40);
  EXPECT_EQ(MadeOn(f.feed->Segment(own.image, 4).get().dynamic_mask), 40);
  f.feed->Stop();
}

TEST(SemanticFeed, AfterAWaitingFrameTheNextIsSegmentedAhead) {
  // As dlslam run calls it: the frame read ahead is offered before the current one is tracked.
  // Frames 1, 2, 3 show squares at x = 5, 40, 60.
  Feed f(/*wait_for_masks=*/false, /*carried_segment_every=*/2);
  f.feed->SegmentAhead(Image(5), 1.0);
  f.feed->SegmentAhead(Image(40), 2.0);
  // A crowded frame waits for its own masks; the network takes the next frame right after it.
  SemanticFeed::FrameMasks m = f.feed->ForFrame(1, Image(5), cv::Mat(), 1.0, /*carry=*/false);
  EXPECT_FALSE(m.segmented_ahead);
  EXPECT_EQ(MadeOn(m.prior().dynamic), 5);
  f.feed->SegmentAhead(Image(60), 3.0);
  // The next frame has its own masks, started ahead, even where carried ones would do...
  m = f.feed->ForFrame(2, Image(40), cv::Mat(), 2.0, /*carry=*/true);
  EXPECT_TRUE(m.segmented_ahead);
  EXPECT_FALSE(m.carried);
  EXPECT_EQ(MadeOn(m.prior().dynamic), 40);
  // ... but does not start the one after it: that frame carries frame 2's masks, published when taken.
  f.feed->SegmentAhead(Image(70), 4.0);
  m = f.feed->ForFrame(3, Image(60), cv::Mat(), 3.0, /*carry=*/true);
  EXPECT_TRUE(m.carried);
  EXPECT_FALSE(m.segmented_ahead);
  const cv::Mat carried = m.prior().dynamic;
  ASSERT_FALSE(carried.empty());
  EXPECT_NE(carried.at<uchar>(15, 44), 0);  // frame 2's square, grown
  EXPECT_EQ(carried.at<uchar>(15, 8), 0);   // not frame 1's
  EXPECT_EQ(f.timings.Summaries().at("semantic_age_frames").max, 1.0);
  f.feed->Stop();
}

}  // namespace
}  // namespace dlslam
