#pragma once
// The fields exchanged between fluid and particles in unresolved CFD-DEM (seed 000, ch. on
// unresolved coupling; seed 001 eqs. for models A/B). All are cell-centred on the fluid grid.
//
//   coupling -> fluid: voidFraction (eps), its previous value (for d eps/dt in continuity),
//                      explicit particle force density (N/m^3) and the implicit drag coefficient
//                      K (kg/m^3/s) so that the fluid feels  -K (u - u_p_avg)  with K in the matrix.
//   fluid -> coupling: cell-centred velocity and pressure gradient (see fluid::Solver).
#include "core/grid.hpp"

namespace gf {

struct CouplingFields {
  Field voidFraction;         // eps in (0, 1], -
  Field voidFractionOld;      // eps at the previous fluid step, -
  Field forceDensity[3];      // explicit force of particles ON the fluid per volume, N/m^3
  Field dragCoefficient;      // implicit coefficient K >= 0 per volume, kg/(m^3 s)
  Field particleVelocity[3];  // K-weighted mean particle velocity per cell, m/s (implicit part: -K(u - this))

  explicit CouplingFields(const CartesianGrid& grid)
      : voidFraction(grid, Staggering::Cell, 1.0),
        voidFractionOld(grid, Staggering::Cell, 1.0),
        forceDensity{Field(grid), Field(grid), Field(grid)},
        dragCoefficient(grid),
        particleVelocity{Field(grid), Field(grid), Field(grid)} {}
  CouplingFields() = default;
};

}  // namespace gf
