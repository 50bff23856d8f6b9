#pragma once
// Short-range lubrication correction of resolved spheres (resolved.lubrication, docs/resolved.md
// sec. 4): the normal force of the thin liquid film between two spheres, or a sphere and a wall or a
// fixed sphere, in the part of the approach the grid does not resolve.
//
// Leading term of the squeeze-film force between two spheres of radii R1, R2 at the surface gap h
// approaching with the normal relative velocity v_n (Brenner 1961, Chem. Eng. Sci. 16, 242; Cox 1974,
// Int. J. Multiphase Flow 1, 343):
//     F = -6 pi mu R_eff^2 / h v_n,   R_eff = R1 R2 / (R1 + R2)   (a wall: R2 -> infinity, R_eff = R1).
// The fictitious-domain forcing resolves the film down to about one cell: the correction adds only
// the part it misses, F(h) - F(h_range), zero for h >= h_range and continuous there, with h clipped
// at h_min below which it stays at its value there (Breugem 2010, ASME FEDSM2010-30634; Kempe &
// Froehlich 2012, J. Fluid Mech. 709, 445), and zero once the surfaces touch (the DEM's contact law
// acts). h_range and h_min are fractions of the smaller diameter of the pair (the particle's for a
// wall).
//
// The force is computed before each DEM sub-step (FictitiousDomain::beforeDemStep): within one fluid step
// the gap can close by much of the range, and the force grows as 1 / h. Over a sub-step dt it is the
// mean of the exact solution of m dv_n/dt = -c v_n, F = -m v_n (1 - exp(-c dt / m)) / dt: -c v_n while
// the film's time scale m / c is long against dt (0.7 ms at h_min for the two-sphere case, against
// 50 us), and never more than the force that stops the normal approach within the sub-step where it
// is not (a viscous liquid, a light particle): the explicit update cannot reverse the approach. m is
// the reduced mass m1 m2 / (m1 + m2) of two particles, the particle's mass against a wall or a fixed
// body.
// Pure functions of scalars (tests/resolved/lubrication_test.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>

namespace gf::resolved {

/// resolved.lubrication: off by default.
struct LubricationSettings {
  bool enabled = false;
  double range = 0.1;    // h_range over the smaller diameter of the pair (about one cell at 8 cells per diameter)
  double minGap = 1e-3;  // h_min over the same diameter
};

/// R1 R2 / (R1 + R2); r2 infinite (a wall): r1.
inline double reducedRadius(double r1, double r2) { return std::isinf(r2) ? r1 : r1 * r2 / (r1 + r2); }

/// The leading-order squeeze-film coefficient c of F = -c v_n at the gap h (Brenner 1961; Cox 1974):
/// 6 pi mu R_eff^2 / h, N s/m.
inline double squeezeFilmCoefficient(double viscosity, double reducedRadius, double gap) {
  return 6.0 * std::numbers::pi * viscosity * reducedRadius * reducedRadius / gap;
}

/// The correction's coefficient: c(max(h, h_min)) - c(h_range) for 0 < h < h_range, 0 at and beyond
/// h_range (Breugem 2010; Kempe & Froehlich 2012), and 0 in contact (h <= 0: the DEM's contact law
/// and its restitution take over). Gaps in m.
inline double lubricationCoefficient(double viscosity, double reducedRadius, double gap, double rangeGap,
                                     double minGap) {
  if (!(gap < rangeGap) || !(minGap < rangeGap) || !(gap > 0.0)) return 0.0;
  const double h = std::max(gap, minGap);
  return squeezeFilmCoefficient(viscosity, reducedRadius, h) - squeezeFilmCoefficient(viscosity, reducedRadius, rangeGap);
}

/// Normal force (along the normal n of v_n = (v_1 - v_2).n) of F = -c v_n averaged over a step dt on
/// a body of reduced mass m: -m v_n (1 - exp(-c dt / m)) / dt (-c v_n for c dt / m << 1).
inline double lubricationForce(double coefficient, double normalVelocity, double reducedMass, double dt) {
  if (coefficient <= 0.0) return 0.0;
  return reducedMass * normalVelocity * std::expm1(-coefficient * dt / reducedMass) / dt;
}

}  // namespace gf::resolved
