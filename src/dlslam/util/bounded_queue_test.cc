#include "dlslam/util/bounded_queue.h"

#include <gtest/gtest.h>

#include <numeric>
#include <thread>
#include <vector>

namespace dlslam {
namespace {

TEST(BoundedQueue, FifoOrder) {
  BoundedQueue<int> q(3);
  EXPECT_TRUE(q.Push(1));
  EXPECT_TRUE(q.Push(2));
  EXPECT_EQ(q.Pop(), 1);
  EXPECT_EQ(q.Pop(), 2);
  EXPECT_EQ(q.TryPop(), std::nullopt);
}

TEST(BoundedQueue, TryPushRefusesWhenFull) {
  BoundedQueue<int> q(1);
  EXPECT_TRUE(q.TryPush(1));
  EXPECT_FALSE(q.TryPush(2));
  EXPECT_EQ(q.size(), 1u);
}

TEST(BoundedQueue, StopDrainsThenEnds) {
  BoundedQueue<int> q(2);
  q.Push(7);
  q.Stop();
  EXPECT_FALSE(q.Push(8));
  EXPECT_EQ(q.Pop(), 7);
  EXPECT_EQ(q.Pop(), std::nullopt);
}

TEST(BoundedQueue, StopWakesBlockedConsumer) {
  BoundedQueue<int> q(1);
  std::optional<int> got = 42;
  std::thread consumer([&] { got = q.Pop(); });
  q.Stop();
  consumer.join();
  EXPECT_EQ(got, std::nullopt);
}

TEST(BoundedQueue, ProducersAndConsumersLoseNothing) {
  BoundedQueue<int> q(4);
  constexpr int kPerProducer = 2000;
  std::vector<std::thread> producers;
  for (int p = 0; p < 2; ++p) {
    producers.emplace_back([&q, p] {
      for (int i = 0; i < kPerProducer; ++i) q.Push(p * kPerProducer + i);
    });
  }
  long long sum = 0;
  std::thread consumer([&] {
    for (int i = 0; i < 2 * kPerProducer; ++i) sum += *q.Pop();
  });
  for (auto& t : producers) t.join();
  consumer.join();
  const int n = 2 * kPerProducer;
  EXPECT_EQ(sum, static_cast<long long>(n) * (n - 1) / 2);
  EXPECT_GT(q.capacity(), 0u);
}

TEST(BoundedQueue, ZeroCapacityIsAnError) { EXPECT_THROW(BoundedQueue<int>(0), Error); }

}  // namespace
}  // namespace dlslam
