// Kernel scheme (QCM-like, cf. Lethe's quadrature-centred method, seed 001 l. 135-231): the
// particle volume is spread over the cells around the particle with the tensor-product kernel
//   W = w(dx/h) w(dy/h) w(dz/h),   w(s) = (1 - s^2)^3 for |s| < 1,
// d = cell centre - particle centre, normalised per particle so the volume is conserved exactly
// (to round-off) whatever h. h = max(factor * max cell size, particle radius); factor >= 1 gives
// a smoothing radius larger than the cell. Per axis, cells beyond a wall are folded back (mirror
// image), beyond a periodic boundary wrapped; being separable, the folded 1D weights multiply
// into distinct cells without any search.
#include <algorithm>
#include <cmath>

#include "coupling/loops.hpp"
#include "coupling/void_fraction/void_fraction_scheme.hpp"

namespace gf::coupling {
namespace {

constexpr int kMaxReach = 32;

/// 1D weights along one axis: mapped cell indices (distinct) and their summed weights.
struct AxisWeights {
  int count = 0;
  int cell[2 * kMaxReach + 1];
  double weight[2 * kMaxReach + 1];
  void add(int c, double w) {
    for (int e = 0; e < count; ++e)
      if (cell[e] == c) {
        weight[e] += w;
        return;
      }
    cell[count] = c;
    weight[count] = w;
    ++count;
  }
};

class KernelVoidFraction final : public VoidFractionScheme {
 public:
  explicit KernelVoidFraction(Params& p)
      : radiusFactor_(p.real({"kernel_radius_cells", "-",
                              "kernel (smoothing) radius of void_fraction: kernel, in units of the largest cell size",
                              Range::between(0.5, 16.0)},
                             1.5)) {}

  void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    const CartesianGrid& g = topology.grid;
    const double cellSize = std::max({g.spacing.x, g.spacing.y, g.spacing.z});
    const double hMax = std::max(radiusFactor_ * cellSize, maxRadius(particles));
    // cell centres within h of a point in cell c lie at offsets |o| < h / dx + 1/2
    std::array<int, 3> reach{};
    int capacity = 1;
    for (int a = 0; a < 3; ++a) {
      reach[a] = std::min(static_cast<int>(std::ceil(hMax / g.spacing[a] + 0.5)), kMaxReach);
      capacity *= std::min(2 * reach[a] + 1, g.cells[a]);
    }
    stencils.resize(particles.size(), capacity);
    forEachIndex(static_cast<std::int64_t>(particles.size()), capacity, [&](std::int64_t p) {
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      const Vec3 x = particles.position[p];
      const double h = std::max(radiusFactor_ * cellSize, particles.radius[p]);
      const auto c = topology.rawCellOf(x);  // unwrapped; neighbours mapped per axis
      AxisWeights axis[3];
      for (int a = 0; a < 3; ++a) {
        for (int o = -reach[a]; o <= reach[a]; ++o) {
          const double s = (g.origin[a] + (c[a] + o + 0.5) * g.spacing[a] - x[a]) / h;
          if (std::abs(s) >= 1.0) continue;
          const double t = 1.0 - s * s;
          axis[a].add(topology.mapIndex(c[a] + o, a), t * t * t);
        }
      }
      for (int k = 0; k < axis[2].count; ++k)
        for (int j = 0; j < axis[1].count; ++j)
          for (int i = 0; i < axis[0].count; ++i)
            w.append(topology.flat(axis[0].cell[i], axis[1].cell[j], axis[2].cell[k]),
                     axis[0].weight[i] * axis[1].weight[j] * axis[2].weight[k]);
      if (w.normalise() <= 0.0) {  // cannot happen for h >= dx / 2; keep the volume anyway
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
                  "smooth tensor-product kernel (1 - s^2)^3 over cells within a radius > cell size, normalised per "
                  "particle (QCM-like)")
}  // namespace gf::coupling
