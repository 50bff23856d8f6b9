#pragma once
// Index loops that stay serial for small work: an OpenMP region costs microseconds (and much more
// on an oversubscribed machine), which dominates the tiny loops of small grids or few particles.
// The choice depends only on the size, so results stay reproducible for a given thread count.
#include <cstdint>

#include "core/parallel.hpp"

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

template <class Body>
inline double sumOverIndices(std::int64_t n, Body&& body) {
  if (n < kMinParallelWork) {
    double s = 0.0;
    for (std::int64_t i = 0; i < n; ++i) s += body(i);
    return s;
  }
  return parallelSum(n, body);
}

}  // namespace gf::coupling
