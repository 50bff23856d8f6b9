#pragma once
// Beetstra, van der Hoef & Kuipers (2007), polydisperse (seed 003 eqs. 3.17-3.20):
//   F*_i = [(1 - phi) y_i + phi y_i^2 + 0.064 (1 - phi) y_i^3] F*(phi, <Re>)        (eq. 3.20)
//   y_i = d_i / <d>, <d> the Sauter mean diameter of the particle's cell (eqs. 3.5, 3.17),
//   <Re> = |U_sf| <d> / nu_f the mixture Reynolds number (eq. 3.19), U_sf = eps (u - v_i),
//   F* the monodisperse Beetstra force (eq. 3.16, beetstra.hpp), normalised with 3 pi mu d_i U_sf,
// so, in the convention of drag_law.hpp (Re = rho |u - v_i| d_i / mu, no eps):
//   <Re>_sup = eps Re / y_i,   f = eps F*_i.
// The published bracket is 1 + 0.064 (1 - phi) at y_i = 1, not 1: in the monodisperse limit this
// law is the monodisperse Beetstra law times 1 + 0.064 eps (0.064 is fitted to bidisperse data;
// test DragLaws.BeetstraPolydisperseMonodisperseLimit). The formula is kept as published.
#include "coupling/drag/beetstra.hpp"

namespace gf::coupling::drag {

/// The bracket of eq. 3.20, [eps y + phi y^2 + 0.064 eps y^3].
inline double beetstraPolydisperseFactor(double sizeRatio, double eps) {
  const double y = sizeRatio, phi = 1.0 - eps;
  return eps * y + phi * y * y + 0.064 * eps * y * y * y;
}

/// f of a particle with size ratio y = d_i / <d> at its own Re (= rho |slip| d_i / mu) and eps.
inline double beetstraPolydisperse(double re, double eps, double sizeRatio) {
  return eps * beetstraPolydisperseFactor(sizeRatio, eps) * beetstraNormalisedForce(eps * re / sizeRatio, eps);
}

}  // namespace gf::coupling::drag
