#pragma once
// Per-stage timing: a stopwatch and a collector of durations that reports
// median, 95th percentile and maximum (the numbers the run report gives).

#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace dlslam {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double ElapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

struct TimingSummary {
  std::size_t count = 0;
  double median = 0.0;  // [ms]
  double p95 = 0.0;     // [ms], nearest rank
  double max = 0.0;     // [ms]
  double total = 0.0;   // [ms]
};

// Summary of a set of durations (empty input -> all zero).
TimingSummary Summarize(std::vector<double> durations_ms);

// Durations per named stage; thread-safe (stages are timed on several threads).
class StageTimings {
 public:
  void Add(const std::string& stage, double ms);
  std::map<std::string, TimingSummary> Summaries() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::vector<double>> durations_;
};

}  // namespace dlslam
