#pragma once
// Simplified JKR cohesion (LIGGGHTS 'cohesion sjkr', Kloss et al. 2012): attractive normal force
// F_c = k_c A with the cohesion energy density k_c (J/m^3) and the geometric contact area
// A = pi a^2, a^2 ~= 2 R* d for small overlaps (chord of two intersecting spheres).
#include <numbers>

namespace gf::dem::cohesion {

inline double simplifiedJkrForce(double cohesionEnergyDensity, double effectiveRadius, double overlap) {
  return cohesionEnergyDensity * 2.0 * std::numbers::pi * effectiveRadius * overlap;
}

}  // namespace gf::dem::cohesion
