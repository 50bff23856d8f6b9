#pragma once
// Index loops that stay serial for small work: an OpenMP region costs microseconds (and much more
// on an oversubscribed machine), which dominates the tiny loops of small grids or few particles.
// The choice depends only on the size, so results stay reproducible for a given thread count.
#include <omp.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/cpu_features.hpp"  // GF_VECTOR_CLONES
#include "core/parallel.hpp"
#include "core/reduction.hpp"

namespace gf::coupling {

inline constexpr std::int64_t kMinParallelWork = 4096;

template <class Body>
inline void forEachIndex(std::int64_t n, std::int64_t workPerIndex, Body&& body) {
  if (n * workPerIndex < kMinParallelWork) {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
    parallelFor(n, body);
  }
}

/// The order of the coupling's reductions (core/reduction.hpp): one accumulator on the calling
/// thread below kMinParallelWork indices, else a fixed block per thread.
inline SumPolicy indexSums() { return {kMinParallelWork, false, false}; }

/// This process's sum of body(i) over [0, n) (gf::localSum in the index order).
template <class Body>
inline double sumOverIndices(std::int64_t n, Body&& body) {
  return gf::localSum(n, indexSums(), body);
}

/// The threads sumsOverRanges runs on for n indices.
inline int threadsForRanges(std::int64_t n) { return n < kMinParallelWork ? 1 : omp_get_max_threads(); }

/// N sums over [0, n), each thread's whole block handed over at once: body(begin, end, sums) adds
/// the terms of indices [begin, end) in index order (the body may work through its block in
/// pieces). On one thread (or for small n) one block [0, n); otherwise each thread sums its static
/// block and the block sums are added in thread order (bit-identical for a given thread count).
template <int N, class Body>
inline std::array<double, N> sumsOverRanges(std::int64_t n, Body&& body, const std::vector<std::size_t>* blocks = nullptr) {
  std::array<double, N> total{};
  const int threads = threadsForRanges(n);
  if (threads == 1) {
    body(std::int64_t{0}, n, total);
    return total;
  }
  std::vector<std::array<double, N>> partial(threads, std::array<double, N>{});
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    const auto [begin, end] = threadBlock(n, t, team, blocks);  // (equal blocks without a split)
    std::array<double, N> local{};
    body(begin, end, local);
    partial[t] = local;
  }
  for (const auto& part : partial)
    for (int c = 0; c < N; ++c) total[c] += part[c];
  return total;
}

/// The same N sums index by index: body(i, sums) adds index i's terms (same blocks, same order,
/// hence the same bits as sumsOverRanges).
template <int N, class Body>
inline std::array<double, N> sumsOverIndices(std::int64_t n, Body&& body, const std::vector<std::size_t>* blocks = nullptr) {
  return sumsOverRanges<N>(
      n,
      [&](std::int64_t begin, std::int64_t end, std::array<double, N>& sums) {
        for (std::int64_t i = begin; i < end; ++i) body(i, sums);
      },
      blocks);
}

/// out[i] = sqrt(in[i]) for i in [0, n), two at a time with SSE2 (IEEE square root per lane: the
/// same bits as std::sqrt; the divider, shared by square roots and divisions, does two at once).
inline void squareRoots(const double* in, double* out, int n) {
  int i = 0;
#if defined(__SSE2__)
  for (; i + 1 < n; i += 2) _mm_storeu_pd(out + i, _mm_sqrt_pd(_mm_loadu_pd(in + i)));
#endif
  for (; i < n; ++i) out[i] = std::sqrt(in[i]);
}

}  // namespace gf::coupling
