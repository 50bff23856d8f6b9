// Volume-averaged (VANS) equations, seed 000 eqs. 5.3 and 5.7 (model A) / seed 001 (model B).
//  - Slab of void fraction eps_s with linear (Darcy) drag K (u - 0): steady one-dimensional flow
//    with superficial velocity U has eps u = U and
//      model A: -eps dp/dx = K u  ->  dp/dx = -K U / eps_s^2
//      model B:     -dp/dx = K u  ->  dp/dx = -K U / eps_s
//    The pressure drop between two planes inside the slab must match within 0.5 %.
//  - Smoothly varying eps(x), no drag, model B: steady 1D flow u = U/eps has
//      p(x1) - p(x2) = rho U^2 (1/eps2 - 1/eps1) + 4/3 mu U (eps'2/eps2 - eps'1/eps1)
//    (full stress of seed 000 eq. 5.6 incl. the transpose and -2/3 div u parts; without them the
//    viscous part would be 3/4 of this).
//  - Time-varying eps: the projection enforces d eps/dt + div(eps u) = 0 cell by cell, so the
//    mass balance sum(eps u . dA) + d/dt sum(eps V) = 0 holds to the solver tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid/sampling.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

const std::string kSlabCase = R"(
domain: {min: [0, 0, 0], max: [1, 0.05, 0.05], periodic: [0, 1, 0]}
fluid:
  density: 1.0
  viscosity: 0.01
  cells: [80, 4, 1]
  pressure: {tolerance: 1e-12}
  boundaries:
    x_min: {type: inlet, velocity: [0.1, 0, 0]}
    x_max: {type: pressure_outlet, pressure: 0}
)";

double slabPressureGradient(const std::string& model, double epsSlab, double K) {
  std::string yaml = kSlabCase;
  yaml.replace(yaml.find("  density"), 0, "  model: " + model + "\n");
  auto c = test::makeCase(yaml);
  Solver& s = *c.solver;
  CouplingFields& cf = s.couplingFields();
  const auto& g = s.grid();
  for (int j = 0; j < g.cells[1]; ++j)
    for (int i = 20; i < 60; ++i) {  // slab 0.25 <= x < 0.75
      cf.voidFraction(i, j, 0) = epsSlab;
      cf.voidFractionOld(i, j, 0) = epsSlab;
      cf.dragCoefficient(i, j, 0) = K;
    }
  for (int n = 0; n < 400; ++n) s.step(0.01);
  // Planes at the cell centres i = 30 and i = 50 (well inside the slab).
  const double dx = (50 - 30) * g.spacing.x;
  const double dp = s.pressure()(50, 1, 0) - s.pressure()(30, 1, 0);
  // Superficial velocity inside the slab equals the inlet velocity.
  EXPECT_NEAR(epsSlab * s.velocity(0)(40, 1, 0), 0.1, 1e-9);
  return dp / dx;
}

TEST(Vans, DarcySlabModelA) {
  const double eps = 0.5, K = 50.0, U = 0.1;
  const double analytic = -K * U / (eps * eps);
  const double g = slabPressureGradient("A", eps, K);
  std::printf("Darcy slab model A: dp/dx %.6f analytic %.6f (rel. %.2e)\n", g, analytic, std::abs(g / analytic - 1));
  EXPECT_NEAR(g, analytic, 5e-3 * std::abs(analytic));
}

TEST(Vans, DarcySlabModelB) {
  const double eps = 0.4, K = 80.0, U = 0.1;
  const double analytic = -K * U / eps;
  const double g = slabPressureGradient("B", eps, K);
  std::printf("Darcy slab model B: dp/dx %.6f analytic %.6f (rel. %.2e)\n", g, analytic, std::abs(g / analytic - 1));
  EXPECT_NEAR(g, analytic, 5e-3 * std::abs(analytic));
}

TEST(Vans, VaryingVoidFractionFullViscousStress) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [1, 0.05, 0.05], periodic: [0, 1, 0]}
fluid:
  model: B
  density: 1.0
  viscosity: 1.0
  convection: central
  cells: [128, 4, 1]
  pressure: {tolerance: 1e-12}
  momentum_tolerance: 1e-12
  boundaries:
    x_min: {type: inlet, velocity: [0.1, 0, 0]}
    x_max: {type: pressure_outlet}
)");
  Solver& s = *c.solver;
  constexpr double kPi = 3.14159265358979323846;
  auto eps = [&](double x) { return 1.0 - 0.4 * std::pow(std::sin(kPi * x), 2); };
  CouplingFields& cf = s.couplingFields();
  const auto& g = s.grid();
  for (int j = 0; j < g.cells[1]; ++j)
    for (int i = 0; i < g.cells[0]; ++i)
      cf.voidFraction(i, j, 0) = cf.voidFractionOld(i, j, 0) = eps(g.cellCentre(i, j, 0).x);
  for (int n = 0; n < 400; ++n) s.step(0.005);
  const double U = 0.1, rho = 1.0, mu = 1.0;
  const double e1 = eps(0.25), e2 = eps(0.5), d1 = -0.4 * kPi * std::sin(2 * kPi * 0.25), d2 = 0.0;
  const double analytic = rho * U * U * (1 / e2 - 1 / e1) + 4.0 / 3.0 * mu * U * (d2 / e2 - d1 / e1);
  const double dp = planeMeanPressure(s, 0, 0.25) - planeMeanPressure(s, 0, 0.5);
  std::printf("varying eps full stress: dp %.6f analytic %.6f (rel. %.2e)\n", dp, analytic, std::abs(dp / analytic - 1));
  EXPECT_NEAR(dp, analytic, 0.01 * analytic);
}

TEST(Vans, UniformEpsAndNoSourcesIsPlainNavierStokes) {
  // eps = 1, K = F = 0 must not change a single bit compared with the same case run before any
  // coupling field was touched (the eps-weighted code path collapses to plain NS).
  auto a = test::makeCase(kSlabCase);
  auto b = test::makeCase(kSlabCase);
  b.solver->couplingFields().voidFraction.fill(1.0);
  for (int n = 0; n < 20; ++n) {
    a.solver->step(0.01);
    b.solver->step(0.01);
  }
  EXPECT_EQ(a.solver->velocity(0).data(), b.solver->velocity(0).data());
  EXPECT_EQ(a.solver->pressure().data(), b.solver->pressure().data());
}

TEST(Vans, MassConservedForTimeVaryingVoidFraction) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [2, 1, 0.1]}
fluid:
  density: 1.0
  viscosity: 0.01
  cells: [64, 32, 1]
  pressure: {tolerance: 1e-11}
  boundaries:
    x_min: {type: inlet, velocity: [0.2, 0, 0]}
    x_max: {type: pressure_outlet}
)");
  Solver& s = *c.solver;
  CouplingFields& cf = s.couplingFields();
  const auto& g = s.grid();
  const double dt = 0.02;
  auto epsAt = [](const Vec3& x, double t) {
    const double cx = 0.5 + 0.5 * t;  // a cloud of particles moving downstream
    return 1.0 - 0.4 * std::exp(-((x.x - cx) * (x.x - cx) + (x.y - 0.5) * (x.y - 0.5)) / 0.02);
  };
  double worstBalance = 0.0, worstCell = 0.0, rateScale = 0.0;
  for (int n = 0; n < 30; ++n) {
    const double t = s.time();
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        cf.voidFractionOld(i, j, 0) = cf.voidFraction(i, j, 0);
        cf.voidFraction(i, j, 0) = epsAt(g.cellCentre(i, j, 0), t + dt);
        rateScale = std::max(rateScale, std::abs(cf.voidFraction(i, j, 0) - cf.voidFractionOld(i, j, 0)) / dt);
      }
    s.step(dt);
    worstCell = std::max(worstCell, s.maxDivergence());
    // Global balance: outflow - inflow + d/dt sum(eps V).
    double storage = 0.0, outflow = 0.0, inflow = 0.0;
    for (int j = 0; j < g.cells[1]; ++j) {
      for (int i = 0; i < g.cells[0]; ++i)
        storage += (cf.voidFraction(i, j, 0) - cf.voidFractionOld(i, j, 0)) / dt * g.cellVolume();
      const double area = g.spacing.y * g.spacing.z;
      inflow += cf.voidFraction(0, j, 0) * s.velocity(0)(0, j, 0) * area;
      outflow += cf.voidFraction(g.cells[0] - 1, j, 0) * s.velocity(0)(g.cells[0], j, 0) * area;
    }
    worstBalance = std::max(worstBalance, std::abs(outflow - inflow + storage) / std::abs(inflow));
  }
  std::printf("time-varying eps: max cell residual %.2e (rate scale %.2f), global balance %.2e\n", worstCell, rateScale,
              worstBalance);
  EXPECT_GT(rateScale, 1.0);  // eps really changes
  EXPECT_LT(worstCell, 1e-8 * rateScale);
  EXPECT_LT(worstBalance, 1e-9);
}

}  // namespace
}  // namespace gf::fluid
