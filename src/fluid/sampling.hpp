#pragma once
// Derived fluid quantities sampled by monitors (and tests): plane averages, flow rates,
// kinetic energy, point probes.
#include <array>

#include "fluid/solver.hpp"

namespace gf::fluid {

/// Mean pressure over the plane x_axis = position (linear between cell centres; blocked cells
/// excluded), Pa.
double planeMeanPressure(const Solver& s, int axis, double position);
/// Volumetric flow rate of the superficial velocity eps u through the face plane nearest to
/// x_axis = position, m^3/s.
double flowRate(const Solver& s, int axis, double position);
/// Kinetic energy  sum 1/2 rho eps |u|^2 V  with cell-centred velocity, J.
double kineticEnergy(const Solver& s);
/// Velocity (3) and pressure at a point (trilinear in cell-centred values).
std::array<double, 4> probe(const Solver& s, const Vec3& point);

}  // namespace gf::fluid
