#pragma once
// Syamlal & O'Brien (1987), as documented for MFIX (Syamlal, Rogers & O'Brien 1993):
//   beta_vol = 3/4 eps phi rho |u - v| / (V_r^2 d) C_D(Re / V_r),  C_D(x) = (0.63 + 4.8/sqrt(x))^2,
//   Re = rho |u - v| d / mu (interstitial slip),
//   V_r = 1/2 (A - 0.06 Re + sqrt((0.06 Re)^2 + 0.12 Re (2B - A) + A^2)),
//   A = eps^4.14,  B = 0.8 eps^1.28 (eps <= 0.85), eps^2.65 (eps > 0.85).
// V_r is the terminal velocity of the suspension over that of one particle (Garside & Al-Dibouni 1977).
// f = beta_vol d^2 / (18 mu phi) = eps Re C_D(Re/V_r) / (24 V_r^2) = eps (0.63 sqrt(Re) + 4.8 sqrt(V_r))^2 / (24 V_r^2).
#include <cmath>

namespace gf::coupling::drag {

inline double syamlalObrienVelocityRatio(double re, double eps) {
  const double a = std::pow(eps, 4.14);
  const double b = eps <= 0.85 ? 0.8 * std::pow(eps, 1.28) : std::pow(eps, 2.65);
  const double r = 0.06 * re;
  return 0.5 * (a - r + std::sqrt(r * r + 2.0 * r * (2.0 * b - a) + a * a));
}

inline double syamlalObrien(double re, double eps) {
  const double vr = syamlalObrienVelocityRatio(re, eps);
  const double s = 0.63 * std::sqrt(re) + 4.8 * std::sqrt(vr);
  return eps * s * s / (24.0 * vr * vr);
}

}  // namespace gf::coupling::drag
