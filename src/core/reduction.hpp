#pragma once
// Reductions of the iterative solvers: the dot products and norms of the Krylov methods (the
// pressure multigrid's conjugate gradients, the momentum predictor's BiCGStab and Jacobi sweeps,
// the coupling's smoothing by conjugate gradients), the sums of per-line partials of their team
// variants, and maxima of per-line partials.
//
// Every reduction is a local sum (or maximum) in a fixed order, followed by its combination across
// processes (sumAcrossRanks, maxAcrossRanks). The combination is the single place where, with the
// grid split among processes, an allreduce goes; in one process it is the identity, so the
// result has the bits of the local sum. The local order is fixed for a thread count: each thread
// sums a fixed block and the partials are added in thread order (gf::parallelSum), or one thread
// sums in index order, as the caller's loop policy (SumPolicy) decides.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <omp.h>

#include "core/parallel.hpp"

namespace gf {

/// How a local sum over n terms is threaded: a subsystem's loop policy (the fluid's element and
/// line loops, the coupling's index loops), so that a reduction sums in the order the subsystem's
/// own loops did.
struct SumPolicy {
  std::int64_t serialBelow = 0;  // fewer terms: summed on the calling thread
  bool serial = false;           // always on the calling thread (a small grid, or one thread)
  /// On the calling thread: interleaved partial sums (four for one sum, serialSum4; two each for
  /// two sums, localSum2) instead of one accumulator. They break the chain of dependent adds.
  bool interleaved = false;
};

/// How partial results combine across the processes of a decomposed grid: allreduces, installed
/// by parallel::RankReductionScope (parallel/reductions.hpp) around the work of a solver whose grid
/// is split among ranks. None installed (one process, or a solver that owns its whole grid): every
/// combination is the identity, and the results have the bits of the local sums. The functions are
/// called on the thread that called MPI (outside OpenMP regions, or by one member of a team).
struct RankReductions {
  double (*sum)(double);
  std::pair<double, double> (*sum2)(std::pair<double, double>);
  double (*max)(double);
};
namespace detail {
inline const RankReductions* activeRankReductions = nullptr;
}  // namespace detail
/// The combination in force (null: none); set through parallel::RankReductionScope.
inline const RankReductions* rankReductions() { return detail::activeRankReductions; }
inline void setRankReductions(const RankReductions* r) { detail::activeRankReductions = r; }

/// The sum of the local sums of all processes. One process: `local` itself.
inline double sumAcrossRanks(double local) {
  const RankReductions* r = detail::activeRankReductions;
  return r ? r->sum(local) : local;
}
/// Two sums combined at once (one message for both, with several processes).
inline std::pair<double, double> sumAcrossRanks(std::pair<double, double> local) {
  const RankReductions* r = detail::activeRankReductions;
  return r ? r->sum2(local) : local;
}
/// The largest of the local maxima of all processes. One process: `local` itself.
inline double maxAcrossRanks(double local) {
  const RankReductions* r = detail::activeRankReductions;
  return r ? r->max(local) : local;
}

/// Sum with four interleaved partial sums in a fixed order (so deterministic): breaks the add
/// latency chain of a single accumulator.
template <class Body>
inline double serialSum4(std::int64_t n, Body&& body) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  std::int64_t i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += body(i);
    s1 += body(i + 1);
    s2 += body(i + 2);
    s3 += body(i + 3);
  }
  for (; i < n; ++i) s0 += body(i);
  return (s0 + s1) + (s2 + s3);
}

/// This process's sum of body(i) over [0, n) (body may also write arrays: fused updates).
template <class Body>
inline double localSum(std::int64_t n, const SumPolicy& policy, Body&& body) {
  if (n < policy.serialBelow || policy.serial) {
    if (policy.interleaved) return serialSum4(n, body);
    double s = 0.0;
    for (std::int64_t i = 0; i < n; ++i) s += body(i);
    return s;
  }
  return gf::parallelSum(n, body);
}

/// This process's two sums in one pass: body(i, a, b) adds to a and b (and may write arrays).
/// Fixed order per thread block, partials added in thread order.
template <class Body>
inline std::pair<double, double> localSum2(std::int64_t n, const SumPolicy& policy, Body&& body) {
  if (n < policy.serialBelow || policy.serial) {
    if (!policy.interleaved) {
      double a = 0.0, b = 0.0;
      for (std::int64_t i = 0; i < n; ++i) body(i, a, b);
      return {a, b};
    }
    double a0 = 0.0, a1 = 0.0, b0 = 0.0, b1 = 0.0;
    std::int64_t i = 0;
    for (; i + 2 <= n; i += 2) {
      body(i, a0, b0);
      body(i + 1, a1, b1);
    }
    for (; i < n; ++i) body(i, a0, b0);
    return {a0 + a1, b0 + b1};
  }
  double pa[256] = {}, pb[256] = {};
#pragma omp parallel
  {
    const int t = omp_get_thread_num();
    double la = 0.0, lb = 0.0;
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) body(i, la, lb);
    pa[t & 255] += la;
    pb[t & 255] += lb;
  }
  double a = 0.0, b = 0.0;
  for (int t = 0; t < 256; ++t) {
    a += pa[t];
    b += pb[t];
  }
  return {a, b};
}

/// The sum of body(i) over the i in [0, n) of every process.
template <class Body>
inline double globalSum(std::int64_t n, const SumPolicy& policy, Body&& body) {
  return sumAcrossRanks(localSum(n, policy, body));
}

/// Two sums of every process in one pass (localSum2).
template <class Body>
inline std::pair<double, double> globalSum2(std::int64_t n, const SumPolicy& policy, Body&& body) {
  return sumAcrossRanks(localSum2(n, policy, body));
}

/// a . b over the n local entries of every process.
inline double dot(const double* a, const double* b, std::int64_t n, const SumPolicy& policy) {
  return globalSum(n, policy, [&](std::int64_t i) { return a[i] * b[i]; });
}
inline double dot(const std::vector<double>& a, const std::vector<double>& b, const SumPolicy& policy) {
  return dot(a.data(), b.data(), static_cast<std::int64_t>(a.size()), policy);
}

/// The Euclidean norm |a| = sqrt(a . a).
inline double norm(const std::vector<double>& a, const SumPolicy& policy) { return std::sqrt(dot(a, a, policy)); }

/// The sum of per-part partial sums (per grid line, filled by the members of a thread team),
/// added in index order, so the same for any split of the parts among the members; then across
/// processes. Team members that all call it get the same value without another barrier (with
/// several processes, one member per process is to combine and share the result instead).
inline double sumOfPartials(const std::vector<double>& partial) {
  double s = 0.0;
  for (double v : partial) s += v;
  return sumAcrossRanks(s);
}

/// The largest of per-part maxima of non-negative values (per grid line; none: 0), then across
/// processes.
inline double maxOfPartials(const std::vector<double>& partial) {
  double m = 0.0;
  for (double v : partial) m = std::max(m, v);
  return maxAcrossRanks(m);
}

}  // namespace gf
