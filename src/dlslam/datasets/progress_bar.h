#pragma once
// A one-line progress bar on stderr, redrawn at most ~8 times a second, and
// only when stderr is a terminal (logs and pipes stay clean). Counts bytes
// (downloads) or items (frames):
//
//   [##########..........]  48.3%  612.0 / 1267.4 MiB  11.2 MiB/s
//   [##########..........]  48.3%  400 / 827 frames  14.2 frames/s

#include <chrono>
#include <cstdint>
#include <string>

namespace dlslam::datasets {

class ProgressBar {
 public:
  // kBytes: amounts shown in MiB. Otherwise amounts are counts of `unit`s.
  static constexpr const char* kBytes = "";

  // Draws nothing unless `enabled` and stderr is a TTY. `unit`: kBytes, or
  // the plural name of what is counted ("frames").
  ProgressBar(std::string label, bool enabled, std::string unit = kBytes);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // done / total in bytes (or units); total = 0 when unknown. `start` = what
  // was already there (not counted in the speed).
  void Update(std::uint64_t done, std::uint64_t total, std::uint64_t start = 0);
  // Ends the line (if one was drawn), so later messages start on a fresh line.
  void Finish();

  // The text of one bar (no "\r"); public for tests.
  static std::string Format(std::uint64_t done, std::uint64_t total, double per_second,
                            const std::string& unit = kBytes);

 private:
  std::string label_;
  bool enabled_;
  std::string unit_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point last_draw_;
  std::uint64_t last_done_ = 0;
};

}  // namespace dlslam::datasets
