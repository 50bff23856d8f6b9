#pragma once
// Gidaspow (1994): Ergun (1952) for eps < 0.8, Wen & Yu (1966) for eps >= 0.8, in the form of
// Zhu et al. (2007) used by CFDEM and Lethe (seed 001 eq. 24-25, seed 003 eq. 3.15):
//   Ergun:  beta_vol = 150 phi^2 mu / (eps d^2) + 1.75 phi rho |u-v| / d
//   Wen-Yu: beta_vol = 3/4 C_D eps phi rho |u-v| / d * eps^-2.65, C_D = Schiller-Naumann(Re_sup)
// With f = beta_vol d^2 / (18 mu phi) (drag_law.hpp):
//   Ergun:  f = 25 phi / (3 eps) + 1.75 Re / 18
//   Wen-Yu: f = C_D Re_sup / 24 * eps^-2.65
// The switch is discontinuous: at eps = 0.8, Re -> 0, Ergun gives 2.083 and Wen-Yu 1.806
// (ratio 1.153). gidaspow_blended removes the jump (Huilin & Gidaspow 2003).
#include <cmath>
#include <numbers>

#include "coupling/drag/single_sphere.hpp"

namespace gf::coupling::drag {

inline double ergun(double re, double eps) {
  const double phi = 1.0 - eps;
  return 25.0 * phi / (3.0 * eps) + 1.75 * re / 18.0;
}

inline double wenYu(double re, double eps) {
  return schillerNaumannFactor(eps * re) * std::pow(eps, -2.65);
}

inline constexpr double kGidaspowSwitchVoidFraction = 0.8;

inline double gidaspow(double re, double eps) {
  return eps < kGidaspowSwitchVoidFraction ? ergun(re, eps) : wenYu(re, eps);
}

/// f[i] = gidaspow(re[i], eps[i]) for i in [0, n), bit for bit: the Ergun branch (two divisions)
/// for all i several at a time in vector registers (AVX-512 / AVX2 clones), then Wen-Yu one by one
/// where eps >= 0.8 (or NaN, as gidaspow).
void gidaspowBlock(const double* re, const double* eps, double* f, int n);

/// Huilin & Gidaspow (2003) blending: w = 1/2 + atan(262.5 (phi - 0.2)) / pi,
/// f = w Ergun + (1 - w) Wen-Yu; continuous in eps.
inline double gidaspowBlended(double re, double eps) {
  const double w = 0.5 + std::atan(262.5 * ((1.0 - eps) - 0.2)) / std::numbers::pi;
  return w * ergun(re, eps) + (1.0 - w) * wenYu(re, eps);
}

}  // namespace gf::coupling::drag
