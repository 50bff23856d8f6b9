#pragma once
// Smoothing of coupling fields by one implicit step of the diffusion equation
//   d phi/dt = D laplace(phi),  D = l^2 / dt  (seed 002 eq. 11, seed 003 eqs. 4.7-4.8)
// i.e.  (I - l^2 laplace) phi_new = phi_old, independent of dt. Zero flux through walls, wrapped
// across periodic boundaries, so sum_c phi_c V_c is conserved (the matrix has unit column sums;
// solved by conjugate gradients to a relative residual 1e-13, so to round-off).
// In 1D on an infinite line the response to a unit impulse is exp(-|x|/l) / (2 l).
#include <cmath>

#include "core/grid.hpp"
#include "coupling/grid_topology.hpp"

namespace gf::coupling {

struct SmoothingReport {
  int iterations = 0;
  double relativeResidual = 0.0;
};

/// Smoothing length for parcels at mean particle volume fraction phi from a length validated at
/// phiRef (seed 003 eq. 4.9-4.10: the parcel's sphere of influence holds the mean concentration,
/// l ~ phi^(-1/3)):  l = lRef (phiRef / phi)^(1/3).  Seed 003 table 4.15 gives l/d32 = 8.06 for
/// coarse-graining ratios 10-25 at phiRef = 1e-3.
inline double scaledSmoothingLength(double lengthAtReference, double referenceVolumeFraction, double volumeFraction) {
  return lengthAtReference * std::cbrt(referenceVolumeFraction / volumeFraction);
}

/// l_smooth / d32 recommended for parcels of coarse-graining ratio alpha at <phi_p> = 1e-3 (seed
/// 003 Tab. 4.15: 8.06 at alpha 10 and 25, 10.3 at 33, 17.0 at 50), linear in alpha between the
/// table's points. Below alpha = 10 the value at 10 (the table holds l/d32 constant up to 25, and
/// Tab. 4.14 shows the uncoarsened suspension insensitive to l); above 50 the line through 33 and 50
/// continued (the seed warns that far beyond its range, e.g. alpha ~ 1000, this grows too large).
inline double recommendedSmoothingRatio(double alpha) {
  constexpr double kAlpha[] = {10.0, 25.0, 33.0, 50.0};
  constexpr double kRatio[] = {8.06, 8.06, 10.3, 17.0};
  if (alpha <= kAlpha[0]) return kRatio[0];
  int i = 0;
  while (i < 2 && alpha > kAlpha[i + 1]) ++i;
  return kRatio[i] + (kRatio[i + 1] - kRatio[i]) * (alpha - kAlpha[i]) / (kAlpha[i + 1] - kAlpha[i]);
}

/// smoothing_length: auto (m): recommendedSmoothingRatio(alpha) d32 at phiRef = 1e-3, scaled to the
/// mean solid fraction <phi_p> by the cube-root law (seed 003 eq. 4.10).
inline double autoSmoothingLength(double alpha, double sauterDiameter, double meanVolumeFraction) {
  return scaledSmoothingLength(recommendedSmoothingRatio(alpha) * sauterDiameter, 1e-3, meanVolumeFraction);
}

/// Smooths the interior cells of `field` in place with smoothing length l (m). l <= 0: no-op.
SmoothingReport smoothField(const GridTopology& topology, double smoothingLength, Field& field);

}  // namespace gf::coupling
