#pragma once
// Filtered drag correction of Radl & Sundaresan (2014) with the parcel correction of Radl &
// Sundaresan (2013) (seed 003 eqs. 3.29-3.36), applied on top of a Beetstra law:
//   beta~ / beta = c_corr(alpha) [1 - f(Delta/L_char, phi) h(phi)]                 (eqs. 3.29, 3.35)
//   f = 1 / (L_char/Delta a(phi) + 1)                                              (eq. 3.32)
//   L_char = u_t^2/g Fr_prim^(-2/3),  Fr_prim = u_t^2 / (d_prim g)                 (eqs. 3.30-3.31)
//   c_corr = a_p + (1 - a_p) exp(-k (alpha - 1)),  a_p = 0, k = 0.05 recommended     (eq. 3.36)
// Delta = cube root of the cell volume (Radl & Sundaresan 2014, p. 418), u_t the terminal velocity
// of an isolated primary particle. a(phi) (eq. 3.33) and h(phi) are the cubic splines of Radl &
// Sundaresan (2014, p. 420); the seed does not print their coefficients: they are taken from that
// paper as implemented in CFDEMcoupling (BeetstraDrag, "useFilteredDragModel"). a is 21.51 below
// phi = 0.016 and 2.47 just above (a step, as published); h -> 0 as phi -> 0, so the correction
// -> 1 in the dilute limit, and -> 1 as Delta -> 0 (a resolved grid needs no correction).
#include <cmath>

#include "coupling/drag/beetstra.hpp"

namespace gf::coupling::drag {

/// One piece of a spline: c0 + c1 x + c2 x^2 + c3 x^3, x = phi - phi0.
inline double splinePiece(double phi, double phi0, double c0, double c1, double c2, double c3) {
  const double x = phi - phi0;
  return c0 + x * (c1 + x * (c2 + x * c3));
}

/// a(phi) of eq. 3.33.
inline double filteredDragA(double phi) {
  if (phi < 0.016) return 21.51;
  if (phi < 0.100) return splinePiece(phi, 0.00, 1.96, 29.40, 164.91, -1923.0);
  if (phi < 0.180) return splinePiece(phi, 0.10, 4.63, 4.68, -412.04, 2254.0);
  if (phi < 0.250) return splinePiece(phi, 0.18, 3.52, -17.99, 128.80, -603.0);
  if (phi < 0.400) return splinePiece(phi, 0.25, 2.68, -8.20, 2.18, 112.33);
  return 1.79;
}

/// h(phi) of eq. 3.29.
inline double filteredDragH(double phi) {
  if (phi < 0.03) return splinePiece(phi, 0.00, 0.0, 7.97, 0.0, 0.0);
  if (phi < 0.08) return splinePiece(phi, 0.03, 0.239, 4.640, -4.410, 253.630);
  if (phi < 0.12) return splinePiece(phi, 0.08, 0.492, 6.100, 33.630, -789.600);
  if (phi < 0.18) return splinePiece(phi, 0.12, 0.739, 5.010, -61.100, 310.800);
  if (phi < 0.34) return splinePiece(phi, 0.18, 0.887, 1.030, -5.170, 5.990);
  if (phi < 0.48) return splinePiece(phi, 0.34, 0.943, -0.170, -2.290, -9.120);
  if (phi < 0.55) return splinePiece(phi, 0.48, 0.850, -1.350, -6.130, -132.600);
  return splinePiece(phi, 0.55, 0.680, -2.340, -225.200, 0.0);
}

/// L_char of eq. 3.31 (m) for terminal velocity u_t (m/s), primary diameter d (m), gravity g (m/s^2).
inline double filteredDragLength(double terminalVelocity, double primaryDiameter, double gravity) {
  const double u2 = terminalVelocity * terminalVelocity;
  const double froude = u2 / (primaryDiameter * gravity);
  return u2 / gravity * std::pow(froude, -2.0 / 3.0);
}

/// 1 - f h of eq. 3.29 at solid fraction phi and filter size Delta (m), L_char (m).
inline double filteredDragCorrection(double phi, double filterSize, double characteristicLength) {
  return 1.0 - filteredDragH(phi) / (characteristicLength / filterSize * filteredDragA(phi) + 1.0);
}

/// c_corr(alpha) of eq. 3.36.
inline double parcelDragCorrection(double coarseGrainingRatio, double a = 0.0, double k = 0.05) {
  return a + (1.0 - a) * std::exp(-k * (coarseGrainingRatio - 1.0));
}

/// Terminal velocity (m/s) of an isolated sphere under the Beetstra law (eps = 1): the root of
/// 3 pi mu d u F*(eps = 1, Re = rho_f u d / mu) = (rho_p - rho_f) g pi d^3 / 6, by bisection
/// (F* grows with Re, so the drag grows with u). Stokes regime: d^2 (rho_p - rho_f) g / (18 mu).
inline double beetstraTerminalVelocity(double diameter, double particleDensity, double fluidDensity,
                                       double viscosity, double gravity) {
  const double weight = std::abs(particleDensity - fluidDensity) * gravity * diameter * diameter / 18.0;  // = mu u_Stokes
  auto excess = [&](double u) {
    return viscosity * u * beetstraNormalisedForce(fluidDensity * u * diameter / viscosity, 1.0) - weight;
  };
  double lo = 0.0, hi = weight / viscosity;  // F* >= 1 at eps = 1: u <= u_Stokes
  while (excess(hi) < 0.0) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace gf::coupling::drag
