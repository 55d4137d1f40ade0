#pragma once
// Turn-taking between a worker that runs steps one after another and the
// threads that sometimes need it held between two steps (loop closing holds
// local mapping while it moves the map). A pause request goes before the
// worker's next step, however much work is queued: with a plain mutex the
// busy worker could take the lock again and again, and loop closing once
// waited 6.8 s for it.

#include <condition_variable>
#include <mutex>

namespace dlslam {

class PauseGate {
 public:
  // Lives as long as a step or a pause; releasing it lets the other side go.
  class Hold {
   public:
    Hold(Hold&& other) noexcept : gate_(other.gate_), pause_(other.pause_) { other.gate_ = nullptr; }
    Hold(const Hold&) = delete;
    Hold& operator=(const Hold&) = delete;
    Hold& operator=(Hold&&) = delete;
    ~Hold() {
      if (gate_ != nullptr) gate_->Release(pause_);
    }

   private:
    friend class PauseGate;
    Hold(PauseGate* gate, bool pause) : gate_(gate), pause_(pause) {}
    PauseGate* gate_;
    bool pause_;
  };

  PauseGate() = default;
  PauseGate(const PauseGate&) = delete;
  PauseGate& operator=(const PauseGate&) = delete;

  // The worker, before a step: waits while paused or while a pause is asked for.
  [[nodiscard]] Hold BeginStep();
  // Any other thread: waits for the step in progress (and for another pause),
  // then holds the worker until the returned Hold is gone.
  [[nodiscard]] Hold Pause();
  // Whether a pause waits: a worker in a long step may cut it short.
  bool pause_requested();

 private:
  void Release(bool pause);

  std::mutex mutex_;
  std::condition_variable changed_;
  int requests_ = 0;      // pauses asked for and not yet granted
  bool paused_ = false;   // a pause is held
  bool stepping_ = false;  // the worker is in a step
};

}  // namespace dlslam
