// Cell-centred pressure gradient next to blocked (solid) cells: a blocked cell has no pressure, so
// the gradient must not difference against it. Water at rest under gravity in a closed box with a
// blocked block in one corner: hydrostatic pressure, so the horizontal gradient is zero everywhere
// (it was ~rho g h / (2 dx) beside the block before the fix, pushing particles into it) and the
// vertical one is -rho g away from walls and blocks.
#include <gtest/gtest.h>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

TEST(BlockedGradient, HydrostaticGradientBesideABlockedRegion) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [0.4, 0.1, 0.4]}
fluid:
  density: 1000.0
  viscosity: 1.0e-3
  cells: [8, 2, 8]
  pressure: {tolerance: 1e-12}
  momentum_tolerance: 1e-12
  boundaries:
    z_max: {type: pressure_outlet}
  blocked:
    - {shape: box, min: [0.3, 0.0, 0.0], max: [0.4, 0.1, 0.2]}
)",
                          Vec3{0.0, 0.0, -9.81});
  Solver& s = *c.solver;
  for (int n = 0; n < 20; ++n) s.step(0.01);
  Field gp[3];
  s.pressureGradient(gp);
  const auto& g = s.grid();
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        if (s.blocked(i, j, k)) continue;
        EXPECT_NEAR(gp[0](i, j, k), 0.0, 1e-3) << i << " " << j << " " << k;  // 1e-7 of rho g
        EXPECT_NEAR(gp[1](i, j, k), 0.0, 1e-3);
      }
  // Interior cell away from walls and the block: the full hydrostatic gradient.
  EXPECT_NEAR(gp[2](2, 0, 4), -1000.0 * 9.81, 1e-6 * 9810.0);
}

}  // namespace
}  // namespace gf::fluid
