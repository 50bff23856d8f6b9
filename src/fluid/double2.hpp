#pragma once
// Two doubles in the lanes of one vector (GCC / Clang vector extension; SSE2 in the generic
// x86-64 build), for the eps = 1 fast paths of the fluid's line kernels. The arithmetic is
// element-wise IEEE arithmetic, as on scalars (scalars are broadcast), and -ffp-contract=off
// keeps a * b + c two roundings: a lane computes the bits of the scalar expression. GCC does not
// vectorise those line loops by itself (selects on the mask, end-of-line cases, in-order sums).
#include <cstring>

namespace gf::fluid {

typedef double Double2 __attribute__((vector_size(16)));

/// Unaligned load of p[0], p[1].
inline Double2 load2(const double* p) {
  Double2 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Unaligned store to p[0], p[1].
inline void store2(double* p, Double2 v) { std::memcpy(p, &v, sizeof v); }

}  // namespace gf::fluid
