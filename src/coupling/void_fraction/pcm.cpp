// Particle centre method: the whole volume goes to the cell containing the centre (seed 001 eq. 6).
#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

class ParticleCentreMethod final : public VoidFractionScheme {
 public:
  explicit ParticleCentreMethod(Params&) {}
  void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    stencils.resize(particles.size(), 1);
    forEachIndex(static_cast<std::int64_t>(particles.size()), 1, [&](std::int64_t p) {
      const auto c = topology.cellOf(particles.position[p]);
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      w.add(topology.flat(c[0], c[1], c[2]), 1.0);
    });
  }
};

}  // namespace
GF_REGISTER_MODEL(VoidFractionScheme, ParticleCentreMethod, "pcm",
                  "particle centre method: the whole particle volume in the cell of its centre")
}  // namespace gf::coupling
