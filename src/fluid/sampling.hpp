#pragma once
// Derived fluid quantities sampled by monitors (and tests): plane averages, flow rates,
// kinetic energy, point probes, profiles along a line.
#include <array>
#include <vector>

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

/// Fields along a grid line: one sample per cell along `axis`, at the cell centres' coordinate on
/// that axis; the other two coordinates are those of `point` (linear between the cell centres
/// there, as probe()).
struct LineProfile {
  std::vector<double> position;                  // coordinate along the axis, m
  std::vector<std::array<double, 3>> velocity;  // cell-centred (mean of the two faces), m/s
  std::vector<double> pressure;                  // Pa
  std::vector<double> voidFraction;              // -
};
LineProfile lineProfile(const Solver& s, int axis, const Vec3& point);

}  // namespace gf::fluid
