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
  // this), at most `ahead` (>= 1) decoded frames waiting.
  FramePrefetcher(const RgbdSequence& sequence, std::size_t count, std::size_t ahead = 2);
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
