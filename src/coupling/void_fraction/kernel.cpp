// Kernel scheme (QCM-like, cf. Lethe's quadrature-centred method, seed 001 l. 135-231): the
// particle volume is spread over all cells whose centre lies within the smoothing radius h of the
// particle centre, with weights W(s) = (1 - s^2)^3, s = |x_cell - x_p| / h, normalised per
// particle, so the volume is conserved exactly (to round-off) whatever h. h = max(factor * max
// cell size, particle radius); factor >= 1 gives a radius larger than the cell. Cells beyond a
// wall are folded back (mirror), beyond a periodic boundary wrapped.
#include <algorithm>
#include <cmath>

#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

class KernelVoidFraction final : public VoidFractionScheme {
 public:
  explicit KernelVoidFraction(Params& p)
      : radiusFactor_(p.real({"kernel_radius_cells", "-",
                              "kernel (smoothing) radius of void_fraction: kernel, in units of the largest cell size",
                              Range::atLeast(0.5)},
                             1.5)) {}

  void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    const CartesianGrid& g = topology.grid;
    const double cellSize = std::max({g.spacing.x, g.spacing.y, g.spacing.z});
    const double hMax = std::max(radiusFactor_ * cellSize, maxRadius(particles));
    std::array<int, 3> reach{};
    int capacity = 1;
    for (int a = 0; a < 3; ++a) {
      reach[a] = static_cast<int>(std::ceil(hMax / g.spacing[a])) + 1;
      capacity *= 2 * reach[a] + 1;
    }
    stencils.resize(particles.size(), capacity);
    forEachIndex(static_cast<std::int64_t>(particles.size()), 27, [&](std::int64_t p) {
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      const Vec3 x = particles.position[p];
      const double h = std::max(radiusFactor_ * cellSize, particles.radius[p]);
      const auto c = g.cellOf(x);  // unwrapped cell, neighbours mapped below
      for (int dk = -reach[2]; dk <= reach[2]; ++dk)
        for (int dj = -reach[1]; dj <= reach[1]; ++dj)
          for (int di = -reach[0]; di <= reach[0]; ++di) {
            const Vec3 d = g.cellCentre(c[0] + di, c[1] + dj, c[2] + dk) - x;
            const double s2 = normSquared(d) / (h * h);
            if (s2 >= 1.0) continue;
            const double t = 1.0 - s2;
            w.add(topology.flatMapped(c[0] + di, c[1] + dj, c[2] + dk), t * t * t);
          }
      if (w.normalise() <= 0.0) {  // cannot happen for h >= cell diagonal / 2; keep volume anyway
        const auto cc = topology.cellOf(x);
        w.add(topology.flat(cc[0], cc[1], cc[2]), 1.0);
      }
    });
  }

 private:
  double radiusFactor_;
};

}  // namespace
GF_REGISTER_MODEL(VoidFractionScheme, KernelVoidFraction, "kernel",
                  "smooth kernel (1 - s^2)^3 over cells within a radius > cell size, normalised per particle (QCM-like)")
}  // namespace gf::coupling
