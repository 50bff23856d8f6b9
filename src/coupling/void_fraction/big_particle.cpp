// Big-particle scheme: for particles as large as or larger than cells. The sphere is sampled by a
// cubic lattice of points (n per diameter, aligned with the particle centre, only points inside
// the sphere kept); each point carries an equal share of the volume and goes to the cell that
// contains it (wrapped / folded at boundaries). The volume fraction of each overlapped cell is
// thus its overlap volume to O(1/n) (a cell fully inside the sphere gets its full volume), and
// the total is conserved exactly by normalisation. Cf. CFDEM 'bigParticle' / Lethe SPM refinement.
#include <algorithm>
#include <cmath>

#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

class BigParticleVoidFraction final : public VoidFractionScheme {
 public:
  explicit BigParticleVoidFraction(Params& p)
      : samples_(static_cast<int>(p.integer({"samples_per_diameter", "-",
                                              "sampling points per particle diameter of void_fraction: big_particle",
                                              Range::between(2, 64)},
                                             10))) {}

  void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    const CartesianGrid& g = topology.grid;
    const double rMax = maxRadius(particles);
    int capacity = 1;
    for (int a = 0; a < 3; ++a) capacity *= static_cast<int>(std::ceil(2.0 * rMax / g.spacing[a])) + 2;
    stencils.resize(particles.size(), capacity);
    const int n = samples_;
    forEachIndex(static_cast<std::int64_t>(particles.size()), 64, [&](std::int64_t p) {
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      const Vec3 x = particles.position[p];
      const double r = particles.radius[p];
      const double h = 2.0 * r / n;  // lattice spacing; points at cell-centred offsets (i + 1/2) h - r
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const Vec3 d{(i + 0.5) * h - r, (j + 0.5) * h - r, (k + 0.5) * h - r};
            if (normSquared(d) > r * r) continue;
            const auto c = topology.cellOf(x + d);
            w.add(topology.flat(c[0], c[1], c[2]), 1.0);
          }
      if (w.normalise() <= 0.0) {
        const auto c = topology.cellOf(x);
        w.add(topology.flat(c[0], c[1], c[2]), 1.0);
      }
    });
  }

 private:
  int samples_;
};

}  // namespace
GF_REGISTER_MODEL(VoidFractionScheme, BigParticleVoidFraction, "big_particle",
                  "volume sampled on a lattice inside the sphere and spread over all overlapped cells")
}  // namespace gf::coupling
