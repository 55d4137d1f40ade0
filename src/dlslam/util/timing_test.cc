#include "dlslam/util/timing.h"

#include <gtest/gtest.h>

#include <thread>

namespace dlslam {
namespace {

TEST(Timing, SummaryOfKnownValues) {
  std::vector<double> d;
  for (int i = 1; i <= 100; ++i) d.push_back(i);
  const TimingSummary s = Summarize(d);
  EXPECT_EQ(s.count, 100u);
  EXPECT_DOUBLE_EQ(s.median, 50.5);
  EXPECT_DOUBLE_EQ(s.p95, 95.0);
  EXPECT_DOUBLE_EQ(s.max, 100.0);
  EXPECT_DOUBLE_EQ(s.total, 5050.0);
  EXPECT_DOUBLE_EQ(Summarize({3.0}).p95, 3.0);
  EXPECT_DOUBLE_EQ(Summarize({3.0, 1.0, 2.0}).median, 2.0);
  EXPECT_EQ(Summarize({}).count, 0u);
}

TEST(Timing, StagesFromSeveralThreads) {
  StageTimings t;
  std::thread a([&] { for (int i = 0; i < 500; ++i) t.Add("track", 1.0); });
  std::thread b([&] { for (int i = 0; i < 300; ++i) t.Add("map", 2.0); });
  a.join();
  b.join();
  const auto s = t.Summaries();
  EXPECT_EQ(s.at("track").count, 500u);
  EXPECT_EQ(s.at("map").count, 300u);
  EXPECT_DOUBLE_EQ(s.at("map").median, 2.0);
}

TEST(Timing, StopwatchMovesForward) {
  Stopwatch w;
  EXPECT_GE(w.ElapsedMs(), 0.0);
}

}  // namespace
}  // namespace dlslam
