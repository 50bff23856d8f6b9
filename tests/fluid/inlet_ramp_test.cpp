// Inlet velocity ramp (boundaries.<side>.ramp_time): the prescribed velocity is multiplied by
// min(1, t / ramp_time), evaluated at the new time level of each step. In a duct with an inlet and
// a pressure outlet, incompressibility makes the flux through every section equal the inlet flux,
// so the outlet face velocity follows the ramp exactly (to the solver tolerance).
#include <gtest/gtest.h>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

TEST(InletRamp, FactorIsLinearThenOne) {
  BoundarySide s;
  EXPECT_EQ(rampFactor(s, 0.0), 1.0);  // no ramp
  s.rampTime = 2.0;
  EXPECT_EQ(rampFactor(s, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(rampFactor(s, 0.5), 0.25);
  EXPECT_EQ(rampFactor(s, 2.0), 1.0);
  EXPECT_EQ(rampFactor(s, 7.0), 1.0);
}

double meanOutletVelocity(const Solver& s) {
  const Field& w = s.velocity(2);
  const auto& g = s.grid();
  double sum = 0.0;
  for (int j = 0; j < g.cells[1]; ++j)
    for (int i = 0; i < g.cells[0]; ++i) sum += w(i, j, g.cells[2]);
  return sum / (g.cells[0] * g.cells[1]);
}

TEST(InletRamp, OutflowFollowsTheRampedInlet) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.4]}
fluid:
  density: 1000.0
  viscosity: 1.0e-3
  cells: [4, 4, 16]
  pressure: {tolerance: 1e-12}
  momentum_tolerance: 1e-12
  boundaries:
    x_min: {type: slip}
    x_max: {type: slip}
    y_min: {type: slip}
    y_max: {type: slip}
    z_min: {type: inlet, velocity: [0, 0, 0.2], ramp_time: 1.0}
    z_max: {type: pressure_outlet}
)");
  Solver& s = *c.solver;
  const double dt = 0.01;
  for (int n = 1; n <= 150; ++n) {
    s.step(dt);
    const double expected = 0.2 * std::min(1.0, n * dt / 1.0);
    ASSERT_NEAR(meanOutletVelocity(s), expected, 1e-9) << "step " << n;
  }
}

}  // namespace
}  // namespace gf::fluid
