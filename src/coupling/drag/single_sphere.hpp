#pragma once
// Drag of an isolated sphere, written as f = C_D Re / 24 (see drag_law.hpp), so that Re -> 0 is
// finite. Used by the single-particle laws and inside the voidage laws.
#include <cmath>

namespace gf::coupling::drag {

/// Schiller & Naumann (1933): C_D = 24/Re (1 + 0.15 Re^0.687) for Re < 1000, 0.44 above
/// (seed 003 eq. 3.15, seed 001 eq. 25).
inline double schillerNaumannFactor(double re) {
  return re < 1000.0 ? 1.0 + 0.15 * std::pow(re, 0.687) : 0.44 * re / 24.0;
}

/// Dallavalle (1948): C_D = (0.63 + 4.8/sqrt(Re))^2 (seed 001 eq. 15), so
/// C_D Re / 24 = (0.63 sqrt(Re) + 4.8)^2 / 24 (-> 0.96 as Re -> 0).
inline double dallavalleFactor(double re) {
  const double s = 0.63 * std::sqrt(re) + 4.8;
  return s * s / 24.0;
}

}  // namespace gf::coupling::drag
