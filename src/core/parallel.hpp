#pragma once
// Index-lambda loops (the AMReX ParallelFor habit): kernels are written once as a lambda of an
// index and run on OpenMP threads today, on a GPU later, unchanged. Static scheduling keeps
// the assignment of indices to threads fixed, so results are reproducible for a thread count.
#include <cstddef>
#include <cstdint>

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

inline int threadCount() { return omp_get_max_threads(); }
inline void setThreadCount(int n) {
  if (n > 0) omp_set_num_threads(n);
}

}  // namespace gf
