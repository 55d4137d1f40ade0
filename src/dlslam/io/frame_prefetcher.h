#pragma once
// Reads a sequence's frames ahead of the one being tracked, in a thread of
// its own, as a camera driver delivers them: decoding a 640x480 colour and
// depth PNG pair takes about 10 ms (a third of a 30 Hz frame's budget) and
// need not hold up tracking. Frames come out in order, each once; a bad
// image is its frame's error, as with RgbdSequence::TryLoadFrame.
//
//   FramePrefetcher frames(sequence, sequence.size());
//   while (std::optional<FramePrefetcher::Item> item = frames.Next()) {
//     if (!item->result.ok()) { ...item->result.error... continue; }
//     Track(*item->result.frame);
//   }

#include <cstddef>
#include <exception>
#include <optional>
#include <thread>

#include "dlslam/io/sequence.h"
#include "dlslam/util/bounded_queue.h"

namespace dlslam::io {

class FramePrefetcher {
 public:
  struct Item {
    std::size_t index = 0;
    FrameLoadResult result;
  };

  // Starts reading frames 0 .. count - 1 of `sequence` (which must outlive
  // this), at most `ahead` (>= 1) decoded frames waiting. The reader runs
  // `thread_nice` below the caller's priority (0..19,
  // util/thread_priority.h): with `ahead` frames decoded it has slack, the
  // tracker and the network have none. 5: Bonn full threaded, 4 interleaved
  // pairs, 1.69-1.74x real time vs 1.60-1.67x at 0, never starved.
  FramePrefetcher(const RgbdSequence& sequence, std::size_t count, std::size_t ahead = 2, int thread_nice = 5);
  // Stops reading (frames not taken are dropped) and joins the thread.
  ~FramePrefetcher();
  FramePrefetcher(const FramePrefetcher&) = delete;
  FramePrefetcher& operator=(const FramePrefetcher&) = delete;

  // The next frame, blocking until it is read; nullopt after the last.
  // Rethrows what the reading thread threw other than a bad image's
  // InputError (out of memory, say).
  std::optional<Item> Next();

 private:
  void ReadAll();

  const RgbdSequence& sequence_;
  const std::size_t count_;
  BoundedQueue<Item> queue_;
  std::exception_ptr failure_;  // written before queue_.Stop(), read after Pop saw it stopped
  std::thread reader_;
};

}  // namespace dlslam::io
