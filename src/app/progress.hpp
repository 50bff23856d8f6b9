#pragma once
// Progress report: on a terminal a single updating line (simulated time, % done, steps/s, ETA);
// otherwise one plain line every `interval` seconds of wall time.
#include <chrono>

namespace gf::app {

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
