// Superficial velocity inlet: with particles in the first cells (eps = 0.5) the mass
// flux through the inlet face must be U A (the prescribed velocity is superficial, as a
// fluidisation velocity is), so the outflow flux of the incompressible gas is U A too
// (continuity of the volume-averaged equations, seed 000 eq. 5.3, steady eps). With
// `superficial: false` the face (interstitial) velocity is U and only eps U A enters.
#include <gtest/gtest.h>

#include <cmath>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

double outflowFlux(bool superficial) {
  const std::string yaml = std::string(R"(
domain: {min: [0, 0, 0], max: [0.04, 0.04, 0.16]}
fluid:
  density: 1.2
  viscosity: 1.8e-5
  cells: [4, 4, 16]
  pressure: {tolerance: 1e-12}
  boundaries:
    x_min: {type: slip}
    x_max: {type: slip}
    y_min: {type: wall}
    y_max: {type: wall}
    z_min: {type: inlet, velocity: [0, 0, 0.5], superficial: )") +
                           (superficial ? "true" : "false") + R"(}
    z_max: {type: pressure_outlet}
)";
  auto c = test::makeCase(yaml);
  Solver& s = *c.solver;
  CouplingFields& cf = s.couplingFields();
  const auto& g = s.grid();
  for (int k = 0; k < 3; ++k)  // packed layer in the inlet cells, with drag
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        cf.voidFraction(i, j, k) = 0.5;
        cf.voidFractionOld(i, j, k) = 0.5;
        cf.dragCoefficient(i, j, k) = 100.0;
      }
  for (int n = 0; n < 20; ++n) s.step(1e-3);
  // Top faces (eps = 1 there): flux = sum u_z A.
  double flux = 0.0;
  for (int j = 0; j < g.cells[1]; ++j)
    for (int i = 0; i < g.cells[0]; ++i) flux += s.velocity(2)(i, j, g.cells[2]) * g.spacing.x * g.spacing.y;
  // The inlet face velocity itself is interstitial: U / eps_f.
  EXPECT_NEAR(s.velocity(2)(1, 1, 0), superficial ? 0.5 / 0.5 : 0.5, 1e-12);
  return flux;
}

TEST(SuperficialInlet, OutflowEqualsInletSuperficialFlux) {
  const double area = 0.04 * 0.04, U = 0.5;
  EXPECT_NEAR(outflowFlux(true), U * area, 1e-9 * U * area);
}

TEST(SuperficialInlet, InterstitialOptionLetsOnlyEpsUEnter) {
  const double area = 0.04 * 0.04, U = 0.5;
  EXPECT_NEAR(outflowFlux(false), 0.5 * U * area, 1e-9 * U * area);
}

}  // namespace
}  // namespace gf::fluid
