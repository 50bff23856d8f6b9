#pragma once
// Di Felice (1994) voidage function (seed 001 eq. 17, CFDEM DiFeliceDrag):
//   F_d = 1/2 C_D rho (pi d^2/4) eps^(2-chi) |u-v| (u-v),  C_D = Dallavalle(Re_sup), Re_sup = eps Re
//   chi = 3.7 - 0.65 exp(-(1.5 - log10 Re_sup)^2 / 2)
// so f = C_D Re_sup/24 * eps^(1-chi). Low Re: f -> 0.96 eps^-2.7 (Richardson-Zaki n = 4.7).
#include <algorithm>
#include <cmath>

#include "coupling/drag/single_sphere.hpp"

namespace gf::coupling::drag {

inline double diFeliceExponent(double reSuperficial) {
  const double l = 1.5 - std::log10(std::max(reSuperficial, 1e-300));
  return 3.7 - 0.65 * std::exp(-0.5 * l * l);
}

inline double diFelice(double re, double eps) {
  const double reSup = eps * re;
  return dallavalleFactor(reSup) * std::pow(eps, 1.0 - diFeliceExponent(reSup));
}

}  // namespace gf::coupling::drag
