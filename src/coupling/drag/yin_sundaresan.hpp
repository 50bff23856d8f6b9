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
// The fluid-mediated particle-particle friction of eqs. 3.25-3.27 is not included (the seed
// neglects it for its particle-to-fluid density ratio of O(2300), seed 003 sec. 2.2).
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

}  // namespace gf::coupling::drag
