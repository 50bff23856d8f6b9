#pragma once
// Deposit of per-particle quantities onto cell fields with the particle stencils:
//   field_c += sum_p w_pc value_p        (several channels at once)
// Deterministic for a given thread count: each thread accumulates its static block of particles
// into a private buffer; buffers are then added in thread order per cell. Memory: threads x cells
// per channel (fine for the grids of unresolved CFD-DEM; a colouring scheme would avoid it).
#include <vector>

#include "core/grid.hpp"
#include "coupling/stencil.hpp"

namespace gf::coupling {

/// values: particles x channels, row-major (values[p * channels + c]); fields: one per channel,
/// all on the same grid. Fields are overwritten (zeroed first, ghosts included).
void depositToFields(const ParticleStencils& stencils, const double* values, int channels,
                     const std::vector<Field*>& fields);

}  // namespace gf::coupling
