// Divided / satellite-point scheme (CFDEM 'divided', dividedVoidFraction; seed 001 "SPM"):
// the volume is split into 29 equal parts at the centre and at 28 satellite points, 14 on each of
// two spheres of radius 0.623926 r and 0.917902 r (0.623926 + 0.293976): 8 points at polar angles
// pi/4, 3pi/4 and azimuths pi/4 + k pi/2, and 6 on the coordinate axes. Each part goes to the cell
// containing its point (wrapped at periodic boundaries, folded back at walls).
#include <array>
#include <cmath>

#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

constexpr int kPoints = 29;

std::array<Vec3, kPoints> unitSatellitePoints() {
  std::array<Vec3, kPoints> pts{};
  int n = 0;
  pts[n++] = {0.0, 0.0, 0.0};
  const double pi = 3.14159265358979323846;
  for (double r : {0.623926, 0.623926 + 0.293976}) {
    for (int a = 0; a < 4; ++a) {
      const double zeta = pi / 4.0 + a * pi / 2.0;
      for (double theta : {pi / 4.0, 3.0 * pi / 4.0})
        pts[n++] = {r * std::sin(theta) * std::cos(zeta), r * std::sin(theta) * std::sin(zeta), r * std::cos(theta)};
    }
    for (int axis = 0; axis < 3; ++axis)
      for (double s : {-1.0, 1.0}) {
        Vec3 v{};
        v[axis] = s * r;
        pts[n++] = v;
      }
  }
  return pts;
}

class DividedVoidFraction final : public VoidFractionScheme {
 public:
  explicit DividedVoidFraction(Params&) {}
  void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    static const std::array<Vec3, kPoints> unit = unitSatellitePoints();
    stencils.resize(particles.size(), kPoints);
    forEachIndex(static_cast<std::int64_t>(particles.size()), 29, [&](std::int64_t p) {
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      const Vec3 x = particles.position[p];
      const double r = particles.radius[p];
      for (const Vec3& u : unit) {
        const auto c = topology.cellOf(x + r * u);
        w.add(topology.flat(c[0], c[1], c[2]), 1.0 / kPoints);
      }
      w.normalise();  // sum of 29 x (1/29) is 1 up to round-off; make it 1 to the last bit we can
    });
  }
};

}  // namespace
GF_REGISTER_MODEL(VoidFractionScheme, DividedVoidFraction, "divided",
                  "satellite points: volume split into 29 equal parts at the centre and 28 points inside the sphere (CFDEM 'divided')")
}  // namespace gf::coupling
