#include "dlslam/datasets/progress_bar.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <utility>

namespace dlslam::datasets {

namespace {
constexpr double kMiB = 1024.0 * 1024.0;
constexpr int kBarWidth = 24;
}  // namespace

ProgressBar::ProgressBar(std::string label, bool enabled, std::string unit)
    : label_(std::move(label)),
      enabled_(enabled && isatty(STDERR_FILENO) == 1),
      unit_(std::move(unit)),
      started_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { Finish(); }

std::string ProgressBar::Format(std::uint64_t done, std::uint64_t total, double per_second,
                                const std::string& unit) {
  const bool bytes = unit.empty();
  const std::string speed = bytes ? fmt::format("{:6.1f} MiB/s", per_second / kMiB)
                                  : fmt::format("{:6.1f} {}/s", per_second, unit);
  const auto amount = [&](std::uint64_t n) {
    return bytes ? fmt::format("{:.1f}", static_cast<double>(n) / kMiB) : fmt::format("{}", n);
  };
  const std::string unit_name = bytes ? "MiB" : unit;
  if (total == 0) return fmt::format("{:>9} {}  {}", amount(done), unit_name, speed);
  const double fraction = std::clamp(static_cast<double>(done) / static_cast<double>(total), 0.0, 1.0);
  const int filled = static_cast<int>(fraction * kBarWidth);
  return fmt::format("[{}{}] {:5.1f}%  {} / {} {}  {}", std::string(filled, '#'),
                     std::string(kBarWidth - filled, '.'), 100.0 * fraction, amount(done), amount(total),
                     unit_name, speed);
}

void ProgressBar::Update(std::uint64_t done, std::uint64_t total, std::uint64_t start) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const bool last = total > 0 && done >= total;  // always shown, but only once
  if (drawn_ && (last ? done == last_done_ : now - last_draw_ < std::chrono::milliseconds(125))) return;
  const double seconds = std::chrono::duration<double>(now - started_).count();
  const double speed = seconds > 0 && done > start ? static_cast<double>(done - start) / seconds : 0;
  std::fprintf(stderr, "\r%s %s\033[K", label_.c_str(), Format(done, total, speed, unit_).c_str());
  std::fflush(stderr);
  drawn_ = true;
  last_draw_ = now;
  last_done_ = done;
}

void ProgressBar::Finish() {
  if (!drawn_) return;
  std::fputc('\n', stderr);
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace dlslam::datasets
