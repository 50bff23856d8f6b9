#pragma once
// Rong, Dong & Yu (2013) voidage function, fitted to LBM data (seed 001 eq. 18):
//   as Di Felice, with chi = 2.65 (eps + 1) - (5.3 - 3.5 eps) eps^2 exp(-(1.5 - log10 Re_sup)^2 / 2)
// f = C_D(Re_sup) Re_sup/24 * eps^(1-chi).
#include <algorithm>
#include <cmath>

#include "coupling/drag/single_sphere.hpp"

namespace gf::coupling::drag {

inline double rongExponent(double reSuperficial, double eps) {
  const double l = 1.5 - std::log10(std::max(reSuperficial, 1e-300));
  return 2.65 * (eps + 1.0) - (5.3 - 3.5 * eps) * eps * eps * std::exp(-0.5 * l * l);
}

inline double rong(double re, double eps) {
  const double reSup = eps * re;
  return dallavalleFactor(reSup) * std::pow(eps, 1.0 - rongExponent(reSup, eps));
}

}  // namespace gf::coupling::drag
