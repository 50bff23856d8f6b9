#pragma once
// Wall-clock time per phase of a run (neighbour search, contacts, fluid, ...), reported at the end.
#include <array>
#include <chrono>
#include <string_view>

namespace gf {

/// (Communication: under MPI, the per-step exchanges with other ranks outside the other phases:
/// ghost updates, the rebuild vote; migration and ghost exchange at a list build count as
/// neighbour search.)
enum class Phase { NeighbourSearch, Contacts, Integration, Fluid, PressureSolve, Coupling, Output, Communication, Count };

inline constexpr std::array<std::string_view, static_cast<int>(Phase::Count)> kPhaseNames = {
    "neighbour search", "contacts", "integration", "fluid", "pressure solve", "coupling", "I/O", "communication"};

class PhaseTimers {
 public:
  void add(Phase p, double seconds) { seconds_[static_cast<int>(p)] += seconds; }
  double seconds(Phase p) const { return seconds_[static_cast<int>(p)]; }
  void reset() { seconds_.fill(0.0); }

 private:
  std::array<double, static_cast<int>(Phase::Count)> seconds_{};
};

/// Adds the lifetime of the scope to one phase: `ScopedPhase t(timers, Phase::Contacts);`
class ScopedPhase {
 public:
  ScopedPhase(PhaseTimers& timers, Phase phase)
      : timers_(timers), phase_(phase), start_(std::chrono::steady_clock::now()) {}
  ~ScopedPhase() {
    timers_.add(phase_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  PhaseTimers& timers_;
  Phase phase_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace gf
