#pragma once
// Run-time choice between one thread and a team for a phase of a small fluid grid whose result
// does not depend on the team size (bit-identical either way, e.g. predictMomentumTeam): on an
// idle machine a team of 2 halves the phase; on an oversubscribed one (other processes on the
// cores) every barrier may wait for a descheduled thread and one thread is faster (measured on
// the shared 2-core machine: 0.6 ms serial, 2.5 ms with a passive team, 46 ms with a spinning
// one). The tuner times both (the fastest of the recent calls of each) and keeps the team unless
// it is clearly slower, probing the other choice now and then, less often while the probes confirm
// the choice. Only the speed depends on it.
#include <algorithm>
#include <cstdlib>
#include <cstring>

#include <omp.h>

namespace gf::fluid {

class TeamTuner {
 public:
  /// Team size for the next call: 1 or `team` (the largest useful size).
  int pick(int team) {
    if (team <= 1) return 1;
    if (const int forced = forcedChoice(); forced != 0) return forced > 0 ? team : 1;
    ++calls_;
    // Warm-up: alternate until both have kWarmup samples.
    if (samples_[0] < kWarmup || samples_[1] < kWarmup) return (calls_ & 1) ? team : 1;
    const bool teamKept = teamPreferred();
    if (calls_ >= nextProbe_) {
      probing_ = true;
      nextProbe_ = calls_ + interval_;
      return teamKept ? 1 : team;
    }
    return teamKept ? team : 1;
  }
  /// Wall seconds of a call run with `team` threads.
  void record(int team, double seconds) {
    const int s = team > 1 ? 1 : 0;
    // The fastest of the recent calls (this window and the previous one): on a shared machine
    // single calls are slowed many times over (a preempted or sleeping thread), which would decide
    // a mean; a machine that stays busy raises the minimum within two windows.
    current_[s] = std::min(current_[s], seconds);
    if (++inWindow_[s] == kWindow) {
      previous_[s] = current_[s];
      current_[s] = kNone;
      inWindow_[s] = 0;
    }
    ++samples_[s];
    if (probing_) {
      probing_ = false;
      const bool confirmed = teamPreferred() == (s == 0);  // the probed choice is still not kept
      interval_ = confirmed ? std::min(2 * interval_, kMaxInterval) : kMinInterval;
    }
  }
  /// Recent fastest call of one thread (0) or the team (1), seconds.
  double estimate(int s) const { return std::min(current_[s], previous_[s]); }
  static double now() { return omp_get_wtime(); }
  /// The team is kept unless it is clearly slower than one thread (kTeamTolerance): a phase run
  /// on one thread lets the other threads go to sleep, and the next team call pays for waking
  /// them, so a plain "faster of the two" drifts towards one thread phase after phase. Measured on
  /// the bubbling bed (2 threads, idle machine): the plain comparison kept one thread for the
  /// pressure solve in 3 of 4 calls, 1.84 s for 0.05 s of bed against 1.55 s with the team
  /// throughout; an oversubscribed machine makes the team several times slower, still caught.
  /// Means (even with this tolerance) were decided by single slow calls over a 1 s run: the pressure
  /// solve then took 31 s on 2 threads against 39 s on one; the recent minimum is robust to them.
  bool teamPreferred() const { return estimate(1) < kTeamTolerance * estimate(0); }
  /// Environment override for measurements (profiles of the team on a busy machine, where the
  /// tuner would pick one thread): GF_FLUID_TEAM=team (always the team), serial (always one
  /// thread); unset or anything else: tuned. Only the speed depends on it.
  static int forcedChoice() {
    static const int forced = [] {
      const char* v = std::getenv("GF_FLUID_TEAM");
      if (!v) return 0;
      return std::strcmp(v, "team") == 0 ? 1 : (std::strcmp(v, "serial") == 0 ? -1 : 0);
    }();
    return forced;
  }

 private:
  static constexpr int kWarmup = 4;
  static constexpr double kTeamTolerance = 2.0;
  static constexpr int kWindow = 8;
  static constexpr double kNone = 1e300;
  static constexpr long kMinInterval = 64, kMaxInterval = 4096;
  long calls_ = 0, nextProbe_ = 0, interval_ = kMinInterval;
  bool probing_ = false;
  int samples_[2] = {0, 0};
  double current_[2] = {kNone, kNone}, previous_[2] = {kNone, kNone};
  int inWindow_[2] = {0, 0};
};

}  // namespace gf::fluid
