#pragma once
// Square root for the hot contact loops: the correctly rounded IEEE result (same bits as
// std::sqrt), without the errno branch and library fallback call that std::sqrt carries unless
// the build uses -fno-math-errno (inputs here are never negative).
#include <cmath>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gf::dem {

inline double sqrtNonNegative(double x) {
#if defined(__SSE2__)
  const __m128d v = _mm_set_sd(x);
  return _mm_cvtsd_f64(_mm_sqrt_sd(v, v));
#else
  return std::sqrt(x);
#endif
}

}  // namespace gf::dem
