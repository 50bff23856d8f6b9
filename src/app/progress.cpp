#include "app/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gf::app {

namespace {
std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e9) return "--";
  const long long s = std::llround(seconds);
  if (s >= 3600) return fmt::format("{}h{:02d}m", s / 3600, (s % 3600) / 60);
  if (s >= 60) return fmt::format("{}m{:02d}s", s / 60, s % 60);
  return fmt::format("{}s", s);
}
}  // namespace

WallClockInterval::WallClockInterval(double seconds)
    // (at most 1e9 s: a longer interval would not fit the clock's integer ticks, and never ends)
    : interval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(std::min(seconds, 1e9)))),
      last_(std::chrono::steady_clock::now()) {}

bool WallClockInterval::due() {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < interval_) return false;
  last_ = now;
  return true;
}

ProgressReporter::ProgressReporter(double endTime, double plainInterval, bool quiet)
    : endTime_(endTime),
      plainInterval_(plainInterval),
      quiet_(quiet),
      terminal_(::isatty(STDOUT_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      lastPrint_(start_) {}

void ProgressReporter::update(double simulatedTime, long long step) {
  if (firstStep_ < 0) firstStep_ = step;
  lastStep_ = step;
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double sinceLast = std::chrono::duration<double>(now - lastPrint_).count();
  if (sinceLast < (terminal_ ? 0.25 : plainInterval_)) return;
  lastPrint_ = now;
  print(simulatedTime, step, false);
}

void ProgressReporter::finish(double simulatedTime) {
  if (quiet_) return;
  print(simulatedTime, lastStep_, true);
}

void ProgressReporter::print(double simulatedTime, long long step, bool final) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = endTime_ > 0.0 ? simulatedTime / endTime_ : 1.0;
  const double stepsPerSecond = elapsed > 0.0 && firstStep_ >= 0 ? (step - firstStep_) / elapsed : 0.0;
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  const std::string line = fmt::format("t = {:.6g} s  {:5.1f} %  {:.0f} steps/s  elapsed {}  ETA {}", simulatedTime,
                                       100.0 * fraction, stepsPerSecond, formatDuration(elapsed),
                                       final ? "0s" : formatDuration(eta));
  if (terminal_)
    std::fprintf(stdout, "\r%-90s%s", line.c_str(), final ? "\n" : "");
  else
    std::fprintf(stdout, "%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace gf::app
