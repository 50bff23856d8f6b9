#pragma once
// Square root for the hot contact loops: the correctly rounded IEEE result (same bits as
// std::sqrt). The build uses -fno-math-errno (CMakeLists.txt), so std::sqrt is the plain
// instruction and vectorises in the batched contact loop; without that flag std::sqrt carries an
// errno branch and a library fallback call, which the scalar intrinsic avoids (inputs here are
// never negative).
#include <cmath>
#if defined(__SSE2__) && !defined(__NO_MATH_ERRNO__)
#include <emmintrin.h>
#endif

namespace gf::dem {

inline double sqrtNonNegative(double x) {
#if defined(__SSE2__) && !defined(__NO_MATH_ERRNO__)
  const __m128d v = _mm_set_sd(x);
  return _mm_cvtsd_f64(_mm_sqrt_sd(v, v));
#else
  return std::sqrt(x);
#endif
}

}  // namespace gf::dem
