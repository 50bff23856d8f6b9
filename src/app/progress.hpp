#pragma once
// Progress report: on a terminal a single updating line (simulated time, % done, steps/s, ETA);
// otherwise one plain line every `interval` seconds of wall time.
#include <chrono>

namespace gf::app {

/// True at most once per `seconds` of wall time: due() answers whether that much has passed since
/// it last answered true (or since construction), and restarts the interval when it has.
class WallClockInterval {
 public:
  explicit WallClockInterval(double seconds);
  bool due();

 private:
  std::chrono::steady_clock::duration interval_;
  std::chrono::steady_clock::time_point last_;
};

class ProgressReporter {
 public:
  ProgressReporter(double endTime, double plainInterval, bool quiet);
  void update(double simulatedTime, long long step);
  void finish(double simulatedTime);

 private:
  void print(double simulatedTime, long long step, bool final);
  double endTime_;
  double plainInterval_;
  bool quiet_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastPrint_;
  long long firstStep_ = -1;
  long long lastStep_ = 0;
};

}  // namespace gf::app
