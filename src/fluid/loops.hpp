#pragma once
// Loops of the fluid solver: gf::parallelFor / gf::parallelSum for large ranges, a plain loop
// for small ones (2D and coarse multigrid levels), where starting an OpenMP team costs more
// than the work -- and much more on an oversubscribed machine. Results are deterministic for a
// given thread count either way.
#include <array>
#include <cstdint>
#include <utility>

#include "core/parallel.hpp"
#include "core/reduction.hpp"
#include "fluid/boundary.hpp"
#include "fluid/team_tuner.hpp"

namespace gf::fluid {

inline constexpr std::int64_t kSerialBelow = 2048;           // grid lines
inline constexpr std::int64_t kSerialElementsBelow = 65536;  // single values
inline constexpr std::int64_t kSerialCellsBelow = 32768;     // whole grids stepped serially

/// Set while a grid of fewer than kSerialCellsBelow cells is stepped (SerialFluidScope): every
/// fluid loop then runs serially. A 2 x 30 x 90 bed has 2-cell grid lines and 5400 cells: a
/// thread team per loop costs more than the loop (2 threads were slower than 1).
inline bool& fluidSerialFlag() {
  static bool flag = false;
  return flag;
}
inline bool serialLoops() { return fluidSerialFlag() || gf::threadCount() == 1; }

class SerialFluidScope {
 public:
  explicit SerialFluidScope(bool on) : previous_(fluidSerialFlag()) { fluidSerialFlag() = previous_ || on; }
  ~SerialFluidScope() { fluidSerialFlag() = previous_; }
  SerialFluidScope(const SerialFluidScope&) = delete;
  SerialFluidScope& operator=(const SerialFluidScope&) = delete;

 private:
  bool previous_;
};

/// The z planes [k0, k1) of the cell grid owned by one member of a thread team (fluid steps of
/// small grids run in one parallel region whose members split the planes; see momentum_team.cpp).
/// first / last: the member owning plane 0 / the last plane (and the extra face plane of w).
struct PlaneSlab {
  int k0 = 0, k1 = 0;
  bool first = true, last = true;
  /// Grid lines (j, k), line = j + points[1] k, of a field with these interior points.
  std::int64_t lineBegin(const std::array<int, 3>& points) const { return static_cast<std::int64_t>(k0) * points[1]; }
  std::int64_t lineEnd(const std::array<int, 3>& points) const {
    return static_cast<std::int64_t>(last ? points[2] : k1) * points[1];
  }
  int planeEnd(const std::array<int, 3>& points) const { return last ? points[2] : k1; }
  /// The member's share of a ghost fill of a field with these interior points (fluid/boundary.hpp).
  GhostPlanes ghostPlanes(const std::array<int, 3>& points) const {
    return GhostPlanes{k0, planeEnd(points), first, last, false};
  }
  /// The slab of the calling member of a parallel region started with num_threads(team)
  /// if (team > 1): member t of the team actually delivered gets planes [planes t/m, planes (t+1)/m).
  static PlaneSlab ofCallingMember(int planes, int team) {
    const int t = team > 1 ? omp_get_thread_num() : 0;
    const int members = team > 1 ? omp_get_num_threads() : 1;  // fewer than asked: still all planes
    PlaneSlab slab;
    slab.k0 = planes * t / members;
    slab.k1 = planes * (t + 1) / members;
    slab.first = t == 0;
    slab.last = t == members - 1;
    return slab;
  }
};

/// Runs body(slab) once per member of a team of 1 or maxTeam threads (the tuner's choice), the
/// members splitting `planes` z planes; the body must give the same result for any split.
template <class Body>
inline void runPlaneTeam(TeamTuner& tuner, int maxTeam, int planes, Body&& body) {
  const int team = tuner.pick(maxTeam);
  const double started = TeamTuner::now();
  auto member = [&]() {
    const PlaneSlab slab = PlaneSlab::ofCallingMember(planes, team);
    body(slab);
  };
  runTeam(team, member);  // (a team of one: no region, core/parallel.hpp)
  tuner.record(team, TeamTuner::now() - started);
}

template <class Body>
inline void parallelFor(std::int64_t n, Body&& body) {
  if (n < kSerialBelow || serialLoops()) {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
    gf::parallelFor(n, body);
  }
}

/// Lines [lineBegin, lineEnd) of a kernel on the calling thread (a member of a thread team that
/// has split the lines), or, with lineEnd < 0, all n lines through parallelFor.
template <class Body>
inline void forLines(std::int64_t n, std::int64_t lineBegin, std::int64_t lineEnd, Body&& body) {
  if (lineEnd < 0) {
    parallelFor(n, body);
  } else {
    for (std::int64_t line = lineBegin; line < lineEnd; ++line) body(line);
  }
}

/// parallelFor with a caller's threshold (grid lines below which the loop stays serial).
template <class Body>
inline void parallelForAbove(std::int64_t n, std::int64_t serialBelow, Body&& body) {
  if (n < serialBelow || serialLoops()) {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) body(i);
  }
}

/// The order of the fluid's reductions (core/reduction.hpp): over grid lines (one accumulator on
/// the calling thread below kSerialBelow lines), and over single values (four interleaved ones
/// below kSerialElementsBelow values); serial for a small grid or one thread.
inline SumPolicy lineSums() { return {kSerialBelow, serialLoops(), false}; }
inline SumPolicy elementSums() { return {kSerialElementsBelow, serialLoops(), true}; }

/// This process's sum over grid lines (gf::localSum in the line order).
template <class Body>
inline double parallelSum(std::int64_t n, Body&& body) {
  return gf::localSum(n, lineSums(), body);
}

/// Element-wise loops (vector updates, dot products): cheap bodies, so a larger threshold.
template <class Body>
inline void parallelForElements(std::int64_t n, Body&& body) {
  if (n < kSerialElementsBelow || serialLoops()) {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
    gf::parallelFor(n, body);
  }
}

using gf::serialSum4;

template <class Body>
inline double parallelSumElements(std::int64_t n, Body&& body) {
  return gf::localSum(n, elementSums(), body);
}

/// Two sums in one pass over single values: body(i, a, b) adds to a and b (and may write arrays).
/// This process's sums (gf::localSum2 in the element order).
template <class Body>
inline std::pair<double, double> parallelSum2Elements(std::int64_t n, Body&& body) {
  return gf::localSum2(n, elementSums(), body);
}

}  // namespace gf::fluid
