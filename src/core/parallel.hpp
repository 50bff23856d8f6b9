#pragma once
// Index-lambda loops (the AMReX ParallelFor habit): kernels are written once as a lambda of an
// index and run on OpenMP threads today, on a GPU later, unchanged. Static scheduling keeps
// the assignment of indices to threads fixed, so results are reproducible for a thread count.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <omp.h>

namespace gf {

/// Loops shorter than this run on the calling thread: a parallel region costs microseconds.
inline constexpr std::int64_t kMinParallelLoop = 512;

template <class Body>
inline void parallelFor(std::int64_t n, Body&& body) {
#pragma omp parallel for schedule(static) if (n >= kMinParallelLoop)
  for (std::int64_t i = 0; i < n; ++i) body(i);
}

/// Sum of body(i) over i in [0, n). Each thread sums a fixed block, and the partial sums are
/// added in thread order, so the result is bit-identical for a given thread count.
template <class Body>
inline double parallelSum(std::int64_t n, Body&& body) {
  double partial[256] = {};
#pragma omp parallel if (n >= kMinParallelLoop)
  {
    const int t = omp_get_thread_num();
    double local = 0.0;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) local += body(i);
    partial[t & 255] += local;
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
