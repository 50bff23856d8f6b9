// Big-particle scheme: for particles as large as or larger than cells. The sphere is sampled by a
// cubic lattice of points (n per diameter, aligned with the particle centre, only points inside
// the sphere kept); each point carries an equal share of the volume and goes to the cell that
// contains it (wrapped / folded at boundaries). The volume fraction of each overlapped cell is
// thus its overlap volume to O(1/n) (a cell fully inside the sphere gets its full volume), and
// the total is conserved exactly by normalisation. Cf. CFDEM 'bigParticle' / Lethe SPM refinement.
#include <algorithm>
#include <cmath>
#include <vector>

#include "coupling/loops.hpp"
#include "coupling/void_fraction/void_fraction_scheme.hpp"

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
    std::array<int, 3> box{};  // unwrapped cells a sphere can overlap, per axis
    int capacity = 1;
    for (int a = 0; a < 3; ++a) {
      box[a] = static_cast<int>(std::ceil(2.0 * rMax / g.spacing[a])) + 2;
      capacity *= box[a];
    }
    stencils.resize(particles.size(), capacity);
    const int n = samples_;
    forEachIndex(static_cast<std::int64_t>(particles.size()), n * n * n, [&](std::int64_t p) {
      thread_local std::vector<double> counts;  // points per unwrapped cell of the particle's box
      counts.assign(static_cast<std::size_t>(capacity), 0.0);
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      const Vec3 x = particles.position[p];
      const double r = particles.radius[p];
      const auto lo = topology.rawCellOf(x - Vec3{r, r, r});
      const double h = 2.0 * r / n;  // lattice spacing; points at offsets (i + 1/2) h - r
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const Vec3 d{(i + 0.5) * h - r, (j + 0.5) * h - r, (k + 0.5) * h - r};
            if (normSquared(d) > r * r) continue;
            const auto c = topology.rawCellOf(x + d);
            const int li = std::clamp(c[0] - lo[0], 0, box[0] - 1), lj = std::clamp(c[1] - lo[1], 0, box[1] - 1),
                      lk = std::clamp(c[2] - lo[2], 0, box[2] - 1);
            counts[(static_cast<std::size_t>(lk) * box[1] + lj) * box[0] + li] += 1.0;
          }
      for (int k = 0; k < box[2]; ++k)
        for (int j = 0; j < box[1]; ++j)
          for (int i = 0; i < box[0]; ++i) {
            const double c = counts[(static_cast<std::size_t>(k) * box[1] + j) * box[0] + i];
            if (c > 0.0) w.add(topology.flatMapped(lo[0] + i, lo[1] + j, lo[2] + k), c);
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
