#pragma once
// Beetstra, van der Hoef & Kuipers (2007), monodisperse (seed 003 eqs. 3.10-3.16):
//   F* = F_d / (3 pi mu d U_sf), U_sf = eps (u - v), Re_sup = eps rho |u - v| d / mu
//   F* = 10 phi / eps^2 + eps^2 (1 + 1.5 sqrt(phi))
//        + 0.413 Re_sup / (24 eps^2) (1/eps + 3 phi eps + 8.4 Re_sup^-0.343) / (1 + 10^(3 phi) Re_sup^-(1 + 4 phi)/2)
// so f = eps F*. Creeping isolated sphere: F* = 1.
#include <algorithm>
#include <cmath>

namespace gf::coupling::drag {

inline double beetstraNormalisedForce(double reSup, double eps) {
  const double phi = 1.0 - eps;
  const double re = std::max(reSup, 1e-20);  // the Re term -> 0 as Re -> 0; avoids 0 * inf
  const double eps2 = eps * eps;
  const double inertial = 0.413 * re / (24.0 * eps2) * (1.0 / eps + 3.0 * phi * eps + 8.4 * std::pow(re, -0.343)) /
                          (1.0 + std::pow(10.0, 3.0 * phi) * std::pow(re, -0.5 * (1.0 + 4.0 * phi)));
  return 10.0 * phi / eps2 + eps2 * (1.0 + 1.5 * std::sqrt(phi)) + inertial;
}

inline double beetstra(double re, double eps) { return eps * beetstraNormalisedForce(eps * re, eps); }

}  // namespace gf::coupling::drag
