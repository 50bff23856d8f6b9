#pragma once
// Yin & Sundaresan (2009) polydisperse drag with the mixture Reynolds number of Holloway, Yin &
// Sundaresan (2010) (seed 003 eqs. 3.21-3.24 and 3.28):
//   F*_i = F_i / [3 pi mu d_i (1 - phi)(v_i - u)]                                       (eq. 3.22)
//   F*_i = 1/(1 - phi) + (F*(phi, Re_mix) - 1/(1 - phi)) (a y_i + (1 - a) y_i^2)        (eq. 3.24)
//   a    = 1 - 2.66 phi + 9.096 phi^2 - 11.338 phi^3
//   Re_mix = |dU_mix| (1 - phi) <d> / nu_f,  dU_mix = sum phi_i dU_i / sum phi_i       (eq. 3.28)
// with F* the monodisperse Beetstra force (eq. 3.16), y_i = d_i / <d>, <d> the Sauter mean
// diameter (eq. 3.5). In the convention of drag_law.hpp: f = eps F*_i, and with
// reMix = rho |dU_mix| <d> / mu (no eps), Re_mix = eps reMix. At y_i = 1 with the particle's
// slip as the mixture slip this is the monodisperse Beetstra law (to round-off).
// Fluid-mediated particle-particle friction (eqs. 3.25-3.27, optional: the seed neglects it for its
// particle-to-fluid density ratio of O(2300), sec. 2.2): per unit volume, class i feels
//   sum_{j != i} beta_ij (v_j - v_i),  beta_ij = 2 alpha_ij phi_i phi_j / (phi_i/beta_i + phi_j/beta_j),
//   beta_i = 18 phi_i (1 - phi) mu / d_i^2 F*_i                      (eqs. 3.23, 3.26)
//   alpha_ij = 1.313 log10(min(d_i, d_j) / lambda) - 1.249             (eq. 3.27)
// with lambda the lubrication cutoff length. The sign is that of a friction (it drives the class
// velocities together and cancels in the sum over classes); eq. 3.25 as printed in the seed writes
// it with the opposite sign, which would feed energy into the relative motion. alpha_ij is clamped
// at 0 (it turns negative for lambda > 0.112 min(d_i, d_j), outside the fit's range lambda/d =
// 1e-3 ... 1e-2).
#include <algorithm>
#include <cmath>

#include "coupling/drag/beetstra.hpp"

namespace gf::coupling::drag {

/// a(phi) of eq. 3.24.
inline double yinSundaresanWeight(double phi) { return 1.0 - 2.66 * phi + 9.096 * phi * phi - 11.338 * phi * phi * phi; }

/// f of a particle with size ratio y = d_i / <d>, at eps, in a cell of mixture Reynolds number
/// reMix = rho |dU_mix| <d> / mu.
inline double yinSundaresan(double eps, double sizeRatio, double reMix) {
  const double phi = 1.0 - eps, y = sizeRatio;
  const double a = yinSundaresanWeight(phi);
  const double isolated = 1.0 / eps;
  const double fixed = isolated + (beetstraNormalisedForce(eps * reMix, eps) - isolated) * (a * y + (1.0 - a) * y * y);
  return eps * fixed;
}

/// alpha_ij of eq. 3.27 for the smaller diameter of the pair and the lubrication cutoff lambda (m).
inline double lubricationFactor(double smallerDiameter, double cutoff) {
  return std::max(0.0, 1.313 * std::log10(smallerDiameter / cutoff) - 1.249);
}

/// beta_i of eq. 3.23 (kg/(m^3 s)) from the class's volume fraction, eps, viscosity, diameter and F*_i.
inline double classFrictionCoefficient(double classFraction, double eps, double viscosity, double diameter,
                                       double normalisedForce) {
  return 18.0 * classFraction * eps * viscosity / (diameter * diameter) * normalisedForce;
}

/// beta_ij of eq. 3.26 (kg/(m^3 s)).
inline double pairFrictionCoefficient(double alpha, double phiI, double phiJ, double betaI, double betaJ) {
  return 2.0 * alpha * phiI * phiJ / (phiI / betaI + phiJ / betaJ);
}

}  // namespace gf::coupling::drag
