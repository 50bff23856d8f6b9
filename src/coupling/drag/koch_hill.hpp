#pragma once
// Koch & Hill (2001), in the form of van Buijtenen et al. (2011) used by CFDEM
// (seed 000 eqs. 5.14-5.18, seed 001 eqs. 19-21):
//   F_d = V_p beta / phi (u - v),  beta = 18 mu eps phi / d^2 F,  F = eps (F0(phi) + 1/2 F3(phi) Re_sup)
// so f = eps^2 (F0 + F3 Re_sup / 2).
//   F0 = (1 + 3 sqrt(phi/2) + 135/64 phi ln phi + 16.14 phi) / (1 + 0.681 phi - 8.48 phi^2 + 8.16 phi^3)
//        for phi < 0.4, 10 phi / eps^3 otherwise;   F3 = 0.0673 + 0.212 phi + 0.0232 / eps^5.
// (Seed 001 prints 8.14 for the last coefficient of F0; seed 000 and Koch & Hill print 8.16.)
#include <cmath>

namespace gf::coupling::drag {

inline double kochHillF0(double phi) {
  if (phi >= 0.4) {
    const double eps = 1.0 - phi;
    return 10.0 * phi / (eps * eps * eps);
  }
  const double phiLogPhi = phi > 0.0 ? phi * std::log(phi) : 0.0;
  return (1.0 + 3.0 * std::sqrt(0.5 * phi) + 135.0 / 64.0 * phiLogPhi + 16.14 * phi) /
         (1.0 + 0.681 * phi - 8.48 * phi * phi + 8.16 * phi * phi * phi);
}

inline double kochHillF3(double phi) {
  const double eps = 1.0 - phi;
  const double eps2 = eps * eps;
  return 0.0673 + 0.212 * phi + 0.0232 / (eps2 * eps2 * eps);
}

inline double kochHill(double re, double eps) {
  const double phi = 1.0 - eps;
  return eps * eps * (kochHillF0(phi) + 0.5 * kochHillF3(phi) * eps * re);
}

}  // namespace gf::coupling::drag
