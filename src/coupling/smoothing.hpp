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

/// Smooths the interior cells of `field` in place with smoothing length l (m). l <= 0: no-op.
SmoothingReport smoothField(const GridTopology& topology, double smoothingLength, Field& field);

}  // namespace gf::coupling
