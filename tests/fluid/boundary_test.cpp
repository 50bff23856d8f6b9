// Boundary conditions, blocked cells, monitors.
//  - parabolic inlet + pressure outlet between no-slip walls: developed plane Poiseuille flow,
//    pressure drop between two planes = 8 mu U_max dx / H^2 (White, Viscous Fluid Flow, eq. 3-42),
//    measured through the registered fluid_pressure_drop monitor; flow rate monitor = 2/3 U_max H.
//  - uniform inlet + zero-gradient outflow: outflow equals inflow.
//  - free-slip walls keep a uniform stream uniform.
//  - a blocked cylinder: no flow through solid faces, projection still divergence-free.
#include <gtest/gtest.h>

#include <cmath>

#include "core/monitor.hpp"
#include "fluid/sampling.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

TEST(Boundaries, ParabolicInletPressureOutletGivesPoiseuilleDrop) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [4, 1, 0.1]}
fluid:
  density: 1
  viscosity: 0.1
  cells: [64, 16, 1]
  pressure: {tolerance: 1e-12}
  momentum_tolerance: 1e-13
  boundaries:
    x_min: {type: inlet, velocity: [0.6, 0, 0], profile: parabolic}
    x_max: {type: pressure_outlet, pressure: 5.0}
)");
  Solver& s = *c.solver;
  for (int n = 0; n < 300; ++n) s.step(0.05);
  Params mp = Params::loadString("{type: fluid_pressure_drop, plane_normal: x, position_1: 1.0, position_2: 3.0}", "m.yaml");
  auto drop = Registry<Monitor>::instance().createByName("fluid_pressure_drop", mp);
  Params fp = Params::loadString("{plane_normal: x, position: 2.0}", "f.yaml");
  auto rate = Registry<Monitor>::instance().createByName("fluid_flow_rate", fp);
  RunState st;
  st.fluid = &s;
  const double expected = 8.0 * 0.1 * 0.6 * 2.0 / 1.0;
  EXPECT_NEAR(drop->sample(st)[0], expected, 1e-6 * expected);
  // Discrete flow rate: midpoint sum of the parabola over 16 cells (H^3/6 + h^2 H/12 scaled).
  const double h = 1.0 / 16;
  const double q = 0.6 * 4.0 * (1.0 / 6.0 + h * h / 12.0) * 0.1;
  EXPECT_NEAR(rate->sample(st)[0], q, 1e-9);
  EXPECT_NEAR(s.pressure()(63, 8, 0), 5.0 + 8.0 * 0.1 * 0.6 * 0.5 * 4.0 / 64, 1e-6);
}

TEST(Boundaries, ZeroGradientOutflowConservesMass) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [2, 1, 0.1]}
fluid:
  density: 1
  viscosity: 0.01
  cells: [32, 16, 1]
  boundaries:
    x_min: {type: inlet, velocity: [1, 0, 0]}
    x_max: {type: outflow}
)");
  Solver& s = *c.solver;
  for (int n = 0; n < 40; ++n) s.step(0.02);
  EXPECT_NEAR(flowRate(s, 0, 2.0), flowRate(s, 0, 0.0), 1e-10);
  EXPECT_NEAR(flowRate(s, 0, 1.0), flowRate(s, 0, 0.0), 1e-7);
  EXPECT_LT(s.maxDivergence(), 1e-6);
}

TEST(Boundaries, SlipWallsKeepUniformStream) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [2, 1, 1]}
fluid:
  density: 1
  viscosity: 0.01
  cells: [16, 8, 8]
  boundaries:
    x_min: {type: inlet, velocity: [0.5, 0, 0]}
    x_max: {type: pressure_outlet}
    y_min: {type: slip}
    y_max: {type: slip}
    z_min: {type: slip}
    z_max: {type: slip}
)");
  Solver& s = *c.solver;
  for (int n = 0; n < 20; ++n) s.step(0.05);
  EXPECT_LT(test::maxFaceError(s, 0, [](const Vec3&) { return 0.5; }), 1e-8);
  EXPECT_LT(test::maxFaceError(s, 1, [](const Vec3&) { return 0.0; }), 1e-8);
  EXPECT_LT(test::maxFaceError(s, 2, [](const Vec3&) { return 0.0; }), 1e-8);
}

TEST(Boundaries, BlockedCylinderIsImpermeable) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [3, 1, 0.1]}
fluid:
  density: 1
  viscosity: 0.01
  cells: [96, 32, 1]
  pressure: {tolerance: 1e-10}
  boundaries:
    x_min: {type: inlet, velocity: [1, 0, 0]}
    x_max: {type: pressure_outlet}
  blocked:
    - {shape: cylinder, centre: [0.8, 0.5, 0], axis: z, radius: 0.15}
)");
  Solver& s = *c.solver;
  for (int n = 0; n < 50; ++n) s.step(0.01);
  s.checkHealth(50, s.time());
  const auto& g = s.grid();
  int solid = 0;
  for (int j = 0; j < g.cells[1]; ++j)
    for (int i = 0; i < g.cells[0]; ++i)
      if (s.blocked(i, j, 0)) {
        ++solid;
        EXPECT_EQ(s.velocity(0)(i, j, 0), 0.0);
        EXPECT_EQ(s.velocity(0)(i + 1, j, 0), 0.0);
        EXPECT_EQ(s.velocity(1)(i, j, 0), 0.0);
        EXPECT_EQ(s.velocity(1)(i, j + 1, 0), 0.0);
      }
  EXPECT_GT(solid, 50);
  EXPECT_LT(s.maxDivergence(), 1e-6);
  EXPECT_NEAR(flowRate(s, 0, 3.0), flowRate(s, 0, 0.0), 1e-8);
  // The obstacle accelerates the flow beside it.
  EXPECT_GT(probe(s, Vec3{0.8, 0.85, 0.05})[0], 1.0);
}

TEST(Boundaries, PeriodicMismatchIsACaseError) {
  EXPECT_THROW(test::makeCase("domain: {min: [0, 0, 0], max: [1, 1, 1], periodic: [1, 0, 0]}\n"
                              "fluid: {cells: [4, 4, 4], boundaries: {x_min: {type: wall}}}\n"),
               CaseError);
}

}  // namespace
}  // namespace gf::fluid
