#include "dlslam/io/frame_prefetcher.h"

#include "dlslam/util/check.h"
#include "dlslam/util/thread_priority.h"

namespace dlslam::io {

FramePrefetcher::FramePrefetcher(const RgbdSequence& sequence, std::size_t count, std::size_t ahead, int thread_nice)
    : sequence_(sequence), count_(count), queue_(ahead) {
  DLSLAM_CHECK_LE(count, sequence.size(), "FramePrefetcher: more frames asked than the sequence has");
  DLSLAM_CHECK(thread_nice >= 0 && thread_nice <= 19, "FramePrefetcher: thread_nice {} outside [0, 19]", thread_nice);
  reader_ = std::thread([this, thread_nice] {
    LowerBackgroundPriority(thread_nice, "frame reader");
    ReadAll();
  });
}

FramePrefetcher::~FramePrefetcher() {
  queue_.Stop();
  reader_.join();
}

void FramePrefetcher::ReadAll() {
  try {
    for (std::size_t i = 0; i < count_; ++i) {
      if (!queue_.Push({i, sequence_.TryLoadFrame(i)})) return;  // stopped by the destructor
    }
  } catch (...) {
    failure_ = std::current_exception();
  }
  queue_.Stop();  // Pop drains what was read, then says the end
}

std::optional<FramePrefetcher::Item> FramePrefetcher::Next() {
  std::optional<Item> item = queue_.Pop();
  if (!item && failure_) std::rethrow_exception(failure_);
  return item;
}

}  // namespace dlslam::io
