#include "dlslam/semantic/segmentation_worker.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "dlslam/semantic/label_maps.h"
#include "dlslam/util/check.h"

namespace dlslam::semantic {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A stand-in backend: the frame's blue value is its id; the "person" is a
// 10 x 10 square at x = id. It records the ids it saw and can be held at a
// gate to make the queue fill up.
class FakeSegmenter : public Segmenter {
 public:
  struct Shared {
    std::mutex mutex;
    std::condition_variable changed;
    std::vector<int> seen;
    bool gate_open = true;
    int started = 0;
  };
  explicit FakeSegmenter(Shared* shared) : shared_(shared) { options_.dynamic_margin_px = 0; }

  SegmentationResult Segment(const cv::Mat& bgr) override {
    DLSLAM_CHECK(bgr.type() == CV_8UC3, "fake segmenter needs CV_8UC3");
    const int id = bgr.at<cv::Vec3b>(0, 0)[0];
    {
      std::unique_lock lock(shared_->mutex);
      ++shared_->started;
      shared_->changed.notify_all();
      shared_->changed.wait(lock, [&] { return shared_->gate_open; });
      shared_->seen.push_back(id);
    }
    cv::Mat labels(bgr.size(), CV_8UC1, cv::Scalar(0));
    labels(cv::Rect(id, 10, 10, 10)).setTo(1);
    return ResultFromLabels(labels, bgr.size(), options_);
  }
  const SegmenterOptions& options() const override { return options_; }

 private:
  Shared* shared_;
  SegmenterOptions options_;
};

cv::Mat Frame(int id) { return cv::Mat(40, 80, CV_8UC3, cv::Scalar(id, 0, 0)); }

TEST(SegmentationWorker, ResultsInSubmissionOrder) {
  FakeSegmenter::Shared shared;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared));
  std::vector<std::shared_future<SegmentationResult>> futures;
  for (int id = 0; id < 12; ++id) futures.push_back(worker.Submit(Frame(id)));
  for (int id = 0; id < 12; ++id) {
    const SegmentationResult& r = futures[static_cast<std::size_t>(id)].get();
    EXPECT_EQ(r.dynamic_mask.at<uchar>(15, id), 255) << id;
    EXPECT_EQ(r.propagated_from, 0);
  }
  worker.Stop();
  EXPECT_EQ(shared.seen, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
}

TEST(SegmentationWorker, StopFinishesTheRunningFrameAndFailsThePendingOnes) {
  FakeSegmenter::Shared shared;
  shared.gate_open = false;
  SegmentationWorkerOptions options;
  options.queue_capacity = 3;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared), options);
  std::vector<std::shared_future<SegmentationResult>> futures;
  for (int id = 0; id < 4; ++id) futures.push_back(worker.Submit(Frame(id)));  // 1 running + 3 queued
  {
    std::unique_lock lock(shared.mutex);
    shared.changed.wait(lock, [&] { return shared.started == 1; });
  }
  std::thread stopper([&] { worker.Stop(); });
  while (!worker.stopped()) std::this_thread::yield();
  {
    // Stop() waits for the running frame; let it finish.
    std::lock_guard lock(shared.mutex);
    shared.gate_open = true;
    shared.changed.notify_all();
  }
  stopper.join();
  EXPECT_EQ(futures[0].get().dynamic_mask.at<uchar>(15, 0), 255);
  for (std::size_t i = 1; i < futures.size(); ++i) {
    try {
      futures[i].get();
      ADD_FAILURE() << "pending frame " << i << " has a result after Stop()";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("stopped before"));
    }
  }
  EXPECT_THAT(shared.seen, ElementsAre(0));
  EXPECT_THROW(worker.Submit(Frame(9)), Error);
  worker.Stop();  // idempotent
}

TEST(SegmentationWorker, SegmenterErrorsReachTheFutureAndTheWorkerGoesOn) {
  FakeSegmenter::Shared shared;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared));
  auto bad = worker.Submit(cv::Mat(40, 80, CV_8UC1, cv::Scalar(0)));
  auto good = worker.Submit(Frame(5));
  EXPECT_THROW(bad.get(), Error);
  EXPECT_EQ(good.get().dynamic_mask.at<uchar>(15, 5), 255);
}

TEST(SegmentationWorker, LowerRatePropagatesAndGrowsTheMask) {
  FakeSegmenter::Shared shared;
  SegmentationWorkerOptions options;
  options.segment_every = 3;
  options.propagation_grow_px = 2;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared), options);
  std::vector<std::shared_future<SegmentationResult>> futures;
  for (int id = 0; id < 7; ++id) futures.push_back(worker.Submit(Frame(id + 20)));
  std::vector<int> gaps;
  for (auto& f : futures) gaps.push_back(f.get().propagated_from);
  EXPECT_THAT(gaps, ElementsAre(0, 1, 2, 0, 1, 2, 0));
  worker.Stop();
  EXPECT_THAT(shared.seen, ElementsAre(20, 23, 26));  // only every third frame segmented
  // Frame 2 carries frame 0's square (x = 20..29), grown by 2 x 2 px.
  const cv::Mat& mask = futures[2].get().dynamic_mask;
  EXPECT_EQ(mask.at<uchar>(15, 20 - 4), 255);
  EXPECT_EQ(mask.at<uchar>(15, 20 - 5), 0);
  EXPECT_EQ(mask.at<uchar>(15, 29 + 4), 255);
  EXPECT_EQ(mask.at<uchar>(15, 29 + 5), 0);
  EXPECT_EQ(futures[2].get().seconds, 0.0);
}

TEST(SegmentationWorker, AFailedSegmentationIsNotPropagatedOver) {
  FakeSegmenter::Shared shared;
  SegmentationWorkerOptions options;
  options.segment_every = 2;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared), options);
  auto f0 = worker.Submit(Frame(30));
  auto f1 = worker.Submit(Frame(31));
  auto f2 = worker.Submit(cv::Mat(40, 80, CV_8UC1, cv::Scalar(0)));  // to segment, fails
  auto f3 = worker.Submit(Frame(33));  // would propagate f2: segmented itself instead
  EXPECT_EQ(f1.get().propagated_from, 1);
  EXPECT_THROW(f2.get(), Error);
  EXPECT_EQ(f3.get().propagated_from, 0);
  EXPECT_EQ(f3.get().dynamic_mask.at<uchar>(15, 33), 255);
  worker.Stop();
  EXPECT_THAT(shared.seen, ElementsAre(30, 33));
}

TEST(SegmentationWorker, PropagationRefusesAFrameOfAnotherSize) {
  FakeSegmenter::Shared shared;
  SegmentationWorkerOptions options;
  options.segment_every = 2;
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared), options);
  auto first = worker.Submit(Frame(1));
  auto other_size = worker.Submit(cv::Mat(20, 30, CV_8UC3, cv::Scalar(2, 0, 0)));
  EXPECT_NO_THROW(first.get());
  try {
    other_size.get();
    ADD_FAILURE() << "propagated a mask onto a frame of another size";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot propagate"));
  }
}

TEST(SegmentationWorker, TrySubmitSkipsWhileAFrameWaitsAndLatestPublishesTheNewest) {
  FakeSegmenter::Shared shared;
  shared.gate_open = false;
  SegmentationWorkerOptions options;
  options.queue_capacity = 2;  // room for a Submit beside one TrySubmit
  SegmentationWorker worker(std::make_unique<FakeSegmenter>(&shared), options);
  EXPECT_FALSE(worker.Latest().has_value());
  ASSERT_TRUE(worker.TrySubmit(Frame(1), 101).has_value());
  {
    std::unique_lock lock(shared.mutex);
    shared.changed.wait(lock, [&] { return shared.started == 1; });  // frame 1 is running
  }
  const auto second = worker.TrySubmit(Frame(2), 102);  // waits behind it
  ASSERT_TRUE(second.has_value());
  EXPECT_FALSE(worker.TrySubmit(Frame(3), 103).has_value());  // one waits already: skipped
  auto keyframe = worker.Submit(Frame(4), 104);    // a Submit still gets the free slot
  {
    std::lock_guard lock(shared.mutex);
    shared.gate_open = true;
  }
  shared.changed.notify_all();
  EXPECT_EQ(second->get().dynamic_mask.at<uchar>(15, 2), 255);
  EXPECT_EQ(keyframe.get().dynamic_mask.at<uchar>(15, 4), 255);
  const auto latest = worker.Latest();
  ASSERT_TRUE(latest.has_value());
  EXPECT_EQ(latest->frame_id, 104);
  EXPECT_EQ(latest->result.dynamic_mask.at<uchar>(15, 4), 255);
  worker.Stop();
  EXPECT_EQ(shared.seen, (std::vector<int>{1, 2, 4}));
}

TEST(SegmentationWorker, RefusesBadOptions) {
  FakeSegmenter::Shared shared;
  SegmentationWorkerOptions options;
  options.segment_every = 0;
  EXPECT_THROW(SegmentationWorker(std::make_unique<FakeSegmenter>(&shared), options), Error);
  options = {};
  options.queue_capacity = 0;
  EXPECT_THROW(SegmentationWorker(std::make_unique<FakeSegmenter>(&shared), options), Error);
  EXPECT_THROW(SegmentationWorker(nullptr), Error);
}

}  // namespace
}  // namespace dlslam::semantic
