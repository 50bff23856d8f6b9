#pragma once
// Void-fraction schemes: how a particle's volume is spread over fluid cells. A scheme builds the
// per-particle stencils (weights summing to 1) once per coupling step (one virtual call); the
// same stencils then give eps and distribute the particle forces (Coupler).
//
// Schemes (one file each, selected by name in the case file, key coupling.void_fraction):
//   pcm           particle centre cell (seed 001 eq. 6)
//   divided       29 satellite points of equal weight (CFDEM 'divided'; seed 001 "SPM")
//   kernel        smooth kernel over cells within a radius larger than a cell (QCM-like)
//   big_particle  volume sampled on a sub-lattice inside the sphere, spread over all overlapped cells
#include <cstddef>

#include "coupling/grid_topology.hpp"
#include "coupling/stencil.hpp"
#include "core/params.hpp"
#include "core/registry.hpp"
#include "dem/particles.hpp"

namespace gf::coupling {

class VoidFractionScheme {
 public:
  virtual ~VoidFractionScheme() = default;
  /// Fills `stencils` for every particle of `particles`.
  virtual void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                             ParticleStencils& stencils) const = 0;

  /// The same stencils built in pieces, for a consumer that uses each piece right away (the
  /// Coupler's deposit then reads a stencil from cache just after it is written): beginStencils
  /// sizes `stencils` for `particles` (capacity and counts) and either builds all of them
  /// (returns false) or none (returns true: pieces follow). Then buildStencilRange builds those
  /// of particles [begin, end) into `out` at entries [first, first + end - begin): into
  /// `stencils` itself (first = begin), or into a buffer of the same capacity that holds one
  /// piece (disjoint ranges, any thread, after beginStencils). The default builds everything in
  /// beginStencils. Same stencils as buildStencils, bit for bit.
  virtual bool beginStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                             ParticleStencils& stencils) const {
    buildStencils(particles, topology, stencils);
    return false;
  }
  virtual void buildStencilRange(const dem::ParticleSet& /*particles*/, const GridTopology& /*topology*/,
                                 ParticleStencils& /*out*/, std::size_t /*begin*/, std::size_t /*end*/,
                                 std::size_t /*first*/) const {}
};

/// Largest radius in the set (0 for an empty set).
double maxRadius(const dem::ParticleSet& particles);

}  // namespace gf::coupling
