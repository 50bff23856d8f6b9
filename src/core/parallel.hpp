#pragma once
// Index-lambda loops (the AMReX ParallelFor habit): kernels are written once as a lambda of an
// index and run on OpenMP threads today, on a GPU later, unchanged. Static scheduling keeps
// the assignment of indices to threads fixed, so results are reproducible for a thread count.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <omp.h>

namespace gf {

/// Loops shorter than this run on the calling thread: a parallel region costs microseconds.
inline constexpr std::int64_t kMinParallelLoop = 512;

/// Whether a loop of n iterations runs on the calling thread: short, one thread, or already in a
/// team. No parallel region is opened then, not even one of one thread: libgomp's barrier makes a
/// futex-wake system call in a team of one as well, about a microsecond per region, barrier or
/// worksharing loop (a few ns for a barrier outside any region).
inline bool runsOnCallingThread(std::int64_t n) {
  return n < kMinParallelLoop || omp_get_max_threads() == 1 || omp_in_parallel();
}

/// Runs member() on every member of a team of `team` threads; a team of one is the calling
/// thread itself (no region: see runsOnCallingThread). The members ask omp_get_thread_num() and
/// omp_get_num_threads() as usual (0 and 1 outside a region); their barriers outside a region are
/// free.
template <class Member>
inline void runTeam(int team, Member&& member) {
  if (team > 1) {
#pragma omp parallel num_threads(team)
    member();
  } else {
    member();
  }
}

/// A barrier for the members of one team that synchronise many times per region (the pressure
/// solve's ~96 per call). An OpenMP barrier in libgomp ends with a futex-wake system call also when
/// every member is already there: about five times the cost of this one on two threads
/// (`grainflow bench BM_TeamBarrier --threads 2` gives this one's). The waiters spin a bounded
/// time (kSpins pauses), then sleep in std::atomic::wait, so an oversubscribed machine loses no
/// more than a short spin; the last arriver's notify makes no system call when nobody sleeps (libstdc++ counts the waiters).
/// Memory: the arrivals are acq_rel read-modify-writes and the release is a release store, so all
/// that the members wrote before the barrier is visible to every member after it (as the OpenMP
/// barrier's flush). A team of one (or a region with another member count than `team`: the
/// members then use the OpenMP barrier) costs nothing extra.
class TeamBarrier {
 public:
  explicit TeamBarrier(int team) : team_(team) {}
  TeamBarrier(const TeamBarrier&) = delete;
  TeamBarrier& operator=(const TeamBarrier&) = delete;
  /// Called by every member of the region (the same number of times).
  void wait() {
    if (team_ <= 1) return;
    if (omp_get_num_threads() != team_) {
#pragma omp barrier
      return;
    }
    const unsigned generation = generation_.load(std::memory_order_relaxed);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) == team_ - 1) {
      arrived_.store(0, std::memory_order_relaxed);
      generation_.store(generation + 1, std::memory_order_release);
      generation_.notify_all();
      return;
    }
    for (int spin = 0; spin < kSpins; ++spin) {
      if (generation_.load(std::memory_order_acquire) != generation) return;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    while (generation_.load(std::memory_order_acquire) == generation)
      generation_.wait(generation, std::memory_order_acquire);
  }

 private:
  static constexpr int kSpins = 4000;
  int team_;
  alignas(64) std::atomic<int> arrived_{0};
  alignas(64) std::atomic<unsigned> generation_{0};
};

template <class Body>
inline void parallelFor(std::int64_t n, Body&& body) {
  if (runsOnCallingThread(n)) {
    for (std::int64_t i = 0; i < n; ++i) body(i);
    return;
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) body(i);
}

/// Sum of body(i) over i in [0, n). Each thread sums a fixed block, and the partial sums are
/// added in thread order, so the result is bit-identical for a given thread count.
template <class Body>
inline double parallelSum(std::int64_t n, Body&& body) {
  double partial[256] = {};
  if (runsOnCallingThread(n)) {
    double local = 0.0;  // (as one member would: the same bits)
    for (std::int64_t i = 0; i < n; ++i) local += body(i);
    partial[0] += local;
  } else {
#pragma omp parallel
    {
      const int t = omp_get_thread_num();
      double local = 0.0;
#pragma omp for schedule(static)
      for (std::int64_t i = 0; i < n; ++i) local += body(i);
      partial[t & 255] += local;
    }
  }
  double total = 0.0;
  for (double p : partial) total += p;
  return total;
}

/// Thread t's block [first, second) of [0, n) in a team of `team`: `blocks` when it is a split for
/// this team (size team + 1, blocks[team] == n: e.g. the DEM's split of the particles by contact
/// work, so that a particle's data stay in the cache of the core that moved it), else the static
/// block schedule(static) would give. Deterministic for a split and a team.
inline std::pair<std::int64_t, std::int64_t> threadBlock(std::int64_t n, int t, int team,
                                                         const std::vector<std::size_t>* blocks) {
  if (blocks && blocks->size() == static_cast<std::size_t>(team) + 1 &&
      (*blocks)[team] == static_cast<std::size_t>(n))
    return {static_cast<std::int64_t>((*blocks)[t]), static_cast<std::int64_t>((*blocks)[t + 1])};
  const std::int64_t chunk = n / team, extra = n % team;
  const std::int64_t begin = t * chunk + (t < extra ? t : extra);
  return {begin, begin + chunk + (t < extra ? 1 : 0)};
}

inline int threadCount() { return omp_get_max_threads(); }
inline void setThreadCount(int n) {
  if (n > 0) omp_set_num_threads(n);
}

}  // namespace gf
