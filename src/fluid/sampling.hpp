#pragma once
// Derived fluid quantities sampled by monitors (and tests): plane averages, flow rates,
// kinetic energy, point probes, profiles along a line.
//
// On a decomposed grid (Solver::decomposition() of several ranks) every function is collective:
// all ranks call it and get the value of the whole domain (sums and extrema across the ranks; a
// point value from the rank that owns the point's lower interpolation cell, whose upper
// neighbours may be its ghost cells). On one rank: the local loops alone.
#include <array>
#include <utility>
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
/// A cell field along a grid line as lineProfile: its values at the cell centres along `axis`.
std::vector<double> lineValues(const Solver& s, const Field& f, int axis, const Vec3& point);

/// Where a profile along a line crosses `level` for the last time going up the axis: the largest
/// position at which values[c] >= level > values[c + 1], linear between the two cell centres;
/// the last centre if the profile never falls below, positions[0] - h/2 if it is never at or above.
double lastCrossing(const std::vector<double>& position, const std::vector<double>& values, double level);
/// Largest |u| of the cell-centred velocity over the cells (the largest spurious velocity of a
/// fluid at rest), m/s.
double maxCellSpeed(const Solver& s);

/// The combination of this rank's part with the other ranks' (collective on a decomposed grid;
/// the local value on one rank), for the monitors' own sums and extrema.
double sumOverRanks(const Solver& s, double local);
std::pair<double, double> sumOverRanks(const Solver& s, std::pair<double, double> local);
double maxOverRanks(const Solver& s, double local);
double minOverRanks(const Solver& s, double local);
/// Along `axis`: this rank's local index of global cell (or face) index `global`.
inline int localIndex(const Solver& s, int axis, int global) { return global - s.cellOffset()[axis]; }
/// Whether global cell index `global` along `axis` lies in this rank's box.
inline bool ownsCellAlong(const Solver& s, int axis, int global) {
  const int l = localIndex(s, axis, global);
  return l >= 0 && l < s.grid().cells[axis];
}

}  // namespace gf::fluid
