#include "dlslam/util/thread_priority.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

namespace dlslam {
namespace {

TEST(ThreadPriority, LowersOnlyTheCallingThread) {
  const int before = ThisThreadNice();
  int inside = before;
  bool lowered = false;
  std::thread t([&] {
    lowered = LowerThisThreadPriority(5);
    inside = ThisThreadNice();
  });
  t.join();
#if defined(__linux__)
  ASSERT_TRUE(lowered);
  EXPECT_EQ(inside, std::min(before + 5, 19));
#endif
  EXPECT_EQ(ThisThreadNice(), before);  // the caller's thread is untouched
}

TEST(ThreadPriority, ZeroChangesNothingAndOutOfRangeIsRefused) {
  const int before = ThisThreadNice();
  EXPECT_TRUE(LowerThisThreadPriority(0));
  EXPECT_FALSE(LowerThisThreadPriority(-1));  // raising needs privileges: never attempted
  EXPECT_FALSE(LowerThisThreadPriority(20));
  EXPECT_EQ(ThisThreadNice(), before);
}

}  // namespace
}  // namespace dlslam
