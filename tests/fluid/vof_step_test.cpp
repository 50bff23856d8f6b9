// The fluid step with a VOF mixture (fluid.vof; src/fluid/vof_step.cpp, docs/vof.md): the
// hydrostatic balance across a 1000:1 density jump, the variable-viscosity stress against
// two-layer Couette flow, the conservation and bounds of a collapsing column, each phase's balance
// of a draining tank with and without particles moving through the surface, and the case-file
// errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "core/error.hpp"
#include "core/monitor.hpp"
#include "core/params.hpp"
#include "fluid/sampling.hpp"
#include "fluid/solver.hpp"
#include "fluid_test_util.hpp"
#include "parallel/reductions.hpp"
#include "vof/vof.hpp"

namespace gf::fluid {
namespace {

using test::makeCase;

constexpr double kG = 9.81;

/// Air over water in a 2D tank (x, y; gravity along -y), water below y = level.
std::string tankCase(int nx, int ny, double level, const std::string& top) {
  return "domain: {min: [0, 0, 0], max: [0.1, 0.2, 0.005]}\n"
         "fluid:\n"
         "  cells: [" + std::to_string(nx) + ", " + std::to_string(ny) + ", 1]\n"
         "  pressure: {tolerance: 1.0e-12, max_iterations: 200}\n"
         "  vof:\n"
         "    phases:\n"
         "      - {name: air, density: 1.0, viscosity: 1.8e-5}\n"
         "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
         "    regions:\n"
         "      - {phase: water, min: [0, 0, 0], max: [0.1, " + std::to_string(level) + ", 1]}\n"
         "  boundaries:\n"
         "    y_max: " + top + "\n";
}

// A column at rest with a 1000:1 jump stays at rest: the buoyancy face force -(g.x)_f d rho/dy
// and the gradient of the modified pressure share the face coefficient, and the projection with
// 1/rho_f finds the p* that cancels it (balanced force). The pressure p = p* + rho g.x at the
// bottom cell is the discrete rho g h of the two layers above it.
TEST(VofStep, HydrostaticColumnWithDensityJumpStaysAtRest) {
  for (const std::string top : {"{type: pressure_outlet, pressure: 0.0}", "{type: wall}"}) {
    auto c = makeCase(tankCase(10, 40, 0.1, top), Vec3{0.0, -kG, 0.0});
    Solver& s = *c.solver;
    ASSERT_TRUE(s.vofEnabled());
    for (int n = 0; n < 50; ++n) s.step(1e-3);
    std::printf("hydrostatic column, top %s: max |u| = %.2e m/s\n", top.c_str(), maxCellSpeed(s));
    EXPECT_LT(maxCellSpeed(s), 1e-9) << top;
    // (the interface lies on a face: alpha stays exactly 0 or 1)
    const auto range = vof::fractionRange(s.phaseFraction(1));
    EXPECT_GE(range[0], 0.0);
    EXPECT_LE(range[1], 1.0);
    if (top.find("outlet") != std::string::npos) {
      // Bottom cell centre at y = h/2: water 0.1 - h/2 above it, air 0.1 above that (p = 0 at the top).
      const double h = 0.2 / 40;
      const double exact = 1000.0 * kG * (0.1 - 0.5 * h) + 1.0 * kG * 0.1;
      std::printf("bottom pressure %.12g Pa, exact %.12g Pa\n", s.pressure()(5, 0, 0), exact);
      EXPECT_NEAR(s.pressure()(5, 0, 0), exact, 1e-9 * exact);
    }
  }
}

// The interface inside a cell (alpha = 1/2 in one row) still stays at rest: the mixture row has
// its own rho, and every face between two rows balances with the face density.
TEST(VofStep, HydrostaticColumnWithMixedCellStaysAtRest) {
  auto c = makeCase(tankCase(4, 40, 0.1, "{type: pressure_outlet, pressure: 0.0}"), Vec3{0.0, -kG, 0.0});
  Solver& s = *c.solver;
  // water below row 19, half water in row 20 (y in [0.1, 0.105))
  s.setPhases([](const Vec3& x) { return x.y < 0.1 ? 1 : 0; });
  for (int n = 0; n < 20; ++n) s.step(1e-3);
  std::printf("mixed cell: max |u| = %.2e m/s\n", maxCellSpeed(s));
  EXPECT_LT(maxCellSpeed(s), 1e-9);
}

// Steady Couette flow of two layers (mu 1 below y = 1/2, mu 1/4 above; same density): the shear
// stress tau = U / (1/(2 mu1) + 1/(2 mu2)) is the same in both, so u is piecewise linear. The
// explicit stress with the four-cell edge viscosity is exact away from the interface row and
// first order at it: max error 1.7 % of U at 16 rows, 0.88 % at 32.
TEST(VofStep, TwoLayerCouetteWithVariableViscosity) {
  double previous = 0.0;
  for (int ny : {16, 32}) {
    const std::string yaml =
        "domain: {min: [0, 0, 0], max: [" + std::to_string(2.0 / ny) + ", 1.0, " + std::to_string(1.0 / ny) +
        "], periodic: [1, 0, 0]}\n"
        "fluid:\n"
        "  cells: [2, " + std::to_string(ny) + ", 1]\n"
        "  pressure: {tolerance: 1.0e-12}\n"
        "  vof:\n"
        "    phases:\n"
        "      - {name: thin, density: 1.0, viscosity: 0.25}\n"
        "      - {name: thick, density: 1.0, viscosity: 1.0}\n"
        "    regions:\n"
        "      - {phase: thick, min: [0, 0, 0], max: [1, 0.5, 1]}\n"
        "  boundaries:\n"
        "    y_max: {type: wall, velocity: [1.0, 0.0, 0.0]}\n";
    auto c = makeCase(yaml);
    Solver& s = *c.solver;
    const double h = 1.0 / ny;
    const double dt = 0.2 * h * h;  // diffusion number 0.2 with mu/rho = 1
    for (double t = 0.0; t < 4.0; t += dt) s.step(dt);
    std::printf("two-layer Couette, %d rows: ", ny);
    const double tau = 1.0 / (0.5 / 1.0 + 0.5 / 0.25);
    double err = 0.0;
    for (int j = 0; j < ny; ++j) {
      const double y = (j + 0.5) * h;
      const double exact = y < 0.5 ? tau * y : tau * 0.5 + tau / 0.25 * (y - 0.5);
      err = std::max(err, std::abs(s.velocity(0)(0, j, 0) - exact));
    }
    std::printf("max |u - exact| = %.3e\n", err);
    EXPECT_LT(err, 0.02) << ny;
    if (previous > 0.0) {
      EXPECT_LT(err, 0.6 * previous);
    }
    previous = err;
  }
}

// A collapsing column (dam break, coarse): every phase keeps its volume to round-off and the
// fractions their bounds while the fluid moves at up to 1 m/s.
TEST(VofStep, CollapsingColumnConservesPhasesAndBounds) {
  const std::string yaml =
      "domain: {min: [0, 0, 0], max: [0.2, 0.1, 0.005]}\n"
      "fluid:\n"
      "  cells: [40, 20, 1]\n"
      "  pressure: {tolerance: 1.0e-10}\n"
      "  vof:\n"
      "    phases:\n"
      "      - {name: air, density: 1.2, viscosity: 1.8e-5}\n"
      "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
      "    regions:\n"
      "      - {phase: water, min: [0, 0, 0], max: [0.05, 0.08, 1]}\n";
  auto c = makeCase(yaml, Vec3{0.0, -kG, 0.0});
  Solver& s = *c.solver;
  const parallel::RankReductionScope ranks(s.decomposition());
  const Field& eps = s.couplingFields().voidFraction;
  const double v0 = vof::phaseVolume(s.phaseFraction(1), eps), a0 = vof::phaseVolume(s.phaseFraction(0), eps);
  for (int n = 0; n < 200; ++n) s.step(5e-4);
  EXPECT_GT(maxCellSpeed(s), 0.5);
  std::printf("collapsing column: water volume change %.2e relative\n",
              vof::phaseVolume(s.phaseFraction(1), eps) / v0 - 1.0);
  EXPECT_NEAR(vof::phaseVolume(s.phaseFraction(1), eps), v0, 1e-12 * v0);
  EXPECT_NEAR(vof::phaseVolume(s.phaseFraction(0), eps), a0, 1e-12 * a0);
  for (int i = 0; i < 2; ++i) {
    const auto range = vof::fractionRange(s.phaseFraction(i));
    EXPECT_GE(range[0], -1e-12);
    EXPECT_LE(range[1], 1.0 + 1e-12);
  }
  EXPECT_LT(vof::maxSumError({s.phaseFraction(0), s.phaseFraction(1)}), 1e-12);
}

// The last place where a profile falls through a level (interface_position's formula).
TEST(VofStep, LastCrossingOfAProfile) {
  const std::vector<double> x{0.5, 1.5, 2.5, 3.5, 4.5, 5.5};
  EXPECT_DOUBLE_EQ(lastCrossing(x, {1, 1, 0.75, 0.25, 0, 0}, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(lastCrossing(x, {1, 1, 1, 1, 1, 1}, 0.5), 5.5);   // never below: the last centre
  EXPECT_DOUBLE_EQ(lastCrossing(x, {0, 0, 0, 0, 0, 0}, 0.5), 0.0);   // never above: the first face
  EXPECT_DOUBLE_EQ(lastCrossing(x, {1, 0, 0, 1, 0.5, 0}, 0.5), 4.5);  // a drop above: its upper edge
}

// The monitors of a mixture on the hydrostatic tank: water mass, bounds, and the surface height.
TEST(VofStep, PhaseMassAndInterfaceMonitors) {
  auto c = makeCase(tankCase(10, 40, 0.1, "{type: pressure_outlet, pressure: 0.0}"), Vec3{0.0, -kG, 0.0});
  Solver& s = *c.solver;
  s.step(1e-3);
  RunState state;
  state.fluid = &s;
  Params pm = Params::loadString("phase: water\n", "m.yaml");
  auto mass = Registry<Monitor>::instance().createByName("phase_mass", pm);
  const auto m = mass->sample(state);
  ASSERT_EQ(m.size(), mass->columns().size());
  EXPECT_NEAR(m[0], 1000.0 * 0.1 * 0.1 * 0.005, 1e-14);  // kg
  EXPECT_EQ(m[3], 0.0);                                   // balance
  EXPECT_EQ(m[4], 0.0);
  EXPECT_EQ(m[5], 1.0);
  Params pi = Params::loadString("phase: water\nsearch_axis: y\nsearch_point: [0.05, 0, 0.0025]\n", "m.yaml");
  auto surface = Registry<Monitor>::instance().createByName("interface_position", pi);
  EXPECT_NEAR(surface->sample(state)[0], 0.1, 1e-12);
  Params bad = Params::loadString("phase: oil\n", "m.yaml");
  auto oil = Registry<Monitor>::instance().createByName("phase_mass", bad);
  EXPECT_THROW(oil->sample(state), CaseError);
}

// phase_mass counts the open cells only: blocked cells carry no flux, and a smoothed void fraction
// that reaches into them (coupling.smoothing_length) must not change a phase's mass.
TEST(VofStep, PhaseMassLeavesBlockedCellsOut) {
  const std::string yaml =
      "domain: {min: [0, 0, 0], max: [0.1, 0.2, 0.005]}\n"
      "fluid:\n"
      "  cells: [20, 40, 1]\n"
      "  vof:\n"
      "    phases:\n"
      "      - {name: air, density: 1.0, viscosity: 1.0e-5}\n"
      "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
      "    regions:\n"
      "      - {phase: water, min: [0, 0, 0], max: [0.1, 0.1, 1]}\n"
      "  blocked:\n"
      "    - {shape: box, min: [0.09, 0.0, 0], max: [0.1, 0.2, 1]}\n";
  auto c = makeCase(yaml, Vec3{0.0, -kG, 0.0});
  Solver& s = *c.solver;
  RunState state;
  state.fluid = &s;
  Params pm = Params::loadString("phase: water\n", "m.yaml");
  auto mass = Registry<Monitor>::instance().createByName("phase_mass", pm);
  const double open = 1000.0 * 0.09 * 0.1 * 0.005;  // the water outside the blocked column
  EXPECT_NEAR(mass->sample(state)[0], open, 1e-14);
  Field& eps = s.couplingFields().voidFraction;
  for (int y = 0; y < 40; ++y)
    for (int x = 18; x < 20; ++x) eps(x, y, 0) = 0.7;  // solid fraction smoothed into the wall
  const auto m = mass->sample(state);
  EXPECT_NEAR(m[0], open, 1e-14);
  EXPECT_NEAR(m[3], 0.0, 1e-15);
}

// A water disc carried by a uniform stream of air (periodic, no gravity, no viscosity): the
// momentum moves with the mass that the transport moves, so the control volumes' masses change by
// exactly the mass fluxes and the velocity stays the stream's to round-off while the disc (1000:1)
// crosses the box.
TEST(VofStep, UniformStreamCarriesAHeavyDiscWithoutDisturbingIt) {
  const std::string yaml =
      "domain: {min: [0, 0, 0], max: [1, 1, 0.03125], periodic: [1, 1, 0]}\n"
      "fluid:\n"
      "  cells: [32, 32, 1]\n"
      "  pressure: {tolerance: 1.0e-12}\n"
      "  initial: {velocity: [1.0, 0.5, 0.0]}\n"
      "  vof:\n"
      "    phases:\n"
      "      - {name: air, density: 1.0, viscosity: 0.0}\n"
      "      - {name: water, density: 1000.0, viscosity: 0.0}\n";
  auto c = makeCase(yaml);
  Solver& s = *c.solver;
  s.setPhases([](const Vec3& x) { return (x.x - 0.5) * (x.x - 0.5) + (x.y - 0.5) * (x.y - 0.5) < 0.04 ? 1 : 0; });
  const parallel::RankReductionScope ranks(s.decomposition());
  const double v0 = vof::phaseVolume(s.phaseFraction(1), s.couplingFields().voidFraction);
  for (int n = 0; n < 64; ++n) s.step(1.0 / 128.0);  // Courant 0.25 + 0.125, half a box along x
  double err = 0.0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i)
      err = std::max({err, std::abs(s.velocity(0)(i, j, 0) - 1.0), std::abs(s.velocity(1)(i, j, 0) - 0.5)});
  std::printf("uniform stream with a disc: max |u - U| = %.2e m/s\n", err);
  EXPECT_LT(err, 1e-10);
  EXPECT_NEAR(vof::phaseVolume(s.phaseFraction(1), s.couplingFields().voidFraction), v0, 1e-12 * v0);
  EXPECT_GT(s.phaseFraction(1)(31, 24, 0) + s.phaseFraction(1)(0, 24, 0), 0.5);  // (the disc has moved on)
}

// A tank draining through a slot at the bottom of one side (pressure outlet behind blocked cells):
// the water that leaves through the open side, summed over the substeps, closes the water's volume
// balance to round-off, and the air that comes in through the open top closes the air's.
TEST(VofStep, DrainingTankClosesEachPhasesBalance) {
  const std::string yaml =
      "domain: {min: [0, 0, 0], max: [0.1, 0.2, 0.005]}\n"
      "fluid:\n"
      "  cells: [20, 40, 1]\n"
      "  pressure: {tolerance: 1.0e-10}\n"
      "  vof:\n"
      "    phases:\n"
      "      - {name: air, density: 1.0, viscosity: 1.0e-5}\n"
      "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
      "    regions:\n"
      "      - {phase: water, min: [0, 0, 0], max: [0.1, 0.15, 1]}\n"
      "  blocked:\n"
      "    - {shape: box, min: [0.095, 0.005, 0], max: [0.1, 0.2, 1]}\n"
      "  boundaries:\n"
      "    x_max: {type: pressure_outlet, pressure: 0.0}\n"
      "    y_max: {type: pressure_outlet, pressure: 0.0}\n";
  auto c = makeCase(yaml, Vec3{0.0, -kG, 0.0});
  Solver& s = *c.solver;
  const parallel::RankReductionScope ranks(s.decomposition());
  const Field& eps = s.couplingFields().voidFraction;
  const double w0 = vof::phaseVolume(s.phaseFraction(1), eps), a0 = vof::phaseVolume(s.phaseFraction(0), eps);
  for (int n = 0; n < 400; ++n) s.step(5e-4);
  const double w = vof::phaseVolume(s.phaseFraction(1), eps), a = vof::phaseVolume(s.phaseFraction(0), eps);
  std::printf("drain: water out %.4e m^3 of %.4e; balance %.2e (water), %.2e (air)\n", s.phaseOutflowVolume(1), w0,
              (w + s.phaseOutflowVolume(1) - w0) / w0, (a + s.phaseOutflowVolume(0) - a0) / w0);
  EXPECT_GT(s.phaseOutflowVolume(1), 0.02 * w0);  // (7 % in 0.2 s)
  EXPECT_LT(s.phaseOutflowVolume(0), 0.0);        // air comes in
  EXPECT_NEAR(w + s.phaseOutflowVolume(1), w0, 1e-12 * w0);
  EXPECT_NEAR(a + s.phaseOutflowVolume(0), a0, 1e-12 * w0);
}

// Particles moving through the surface (prescribed solid-volume blobs, no drag) while the tank
// drains through a side slot: the phase transport takes the contents to the void fraction of the
// step's continuity equation, so each phase's mass measured with it (monitor phase_mass) plus its
// outflow stays its initial mass. The blobs bob through the surface, and their displacement moves
// water and air across it: with the fractions left at eps* = 2 eps^n - eps^{n-1} the water's
// balance drifts by the sum of alpha (eps^{n+1} - eps*) V, printed as "extrapolation".
TEST(VofStep, MovingParticlesKeepEachPhasesBalance) {
  const std::string yaml =
      "domain: {min: [0, 0, 0], max: [0.1, 0.2, 0.005]}\n"
      "fluid:\n"
      "  cells: [20, 40, 1]\n"
      "  pressure: {tolerance: 1.0e-12, max_iterations: 200}\n"
      "  vof:\n"
      "    phases:\n"
      "      - {name: air, density: 1.0, viscosity: 1.0e-5}\n"
      "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
      "    regions:\n"
      "      - {phase: water, min: [0, 0, 0], max: [0.1, 0.1, 1]}\n"
      "  blocked:\n"
      "    - {shape: box, min: [0.095, 0.005, 0], max: [0.1, 0.2, 1]}\n"
      "  boundaries:\n"
      "    x_max: {type: pressure_outlet, pressure: 0.0}\n"
      "    y_max: {type: pressure_outlet, pressure: 0.0}\n";
  auto c = makeCase(yaml, Vec3{0.0, -kG, 0.0});
  Solver& s = *c.solver;
  const parallel::RankReductionScope ranks(s.decomposition());
  // three blobs of radius 12 mm, solid fraction 0.5 (1 - r^2/R^2), bobbing 15 mm about the surface
  // with a period of 0.1 s (up to 0.94 m/s), out of phase
  auto voidFraction = [](const Vec3& x, double t) {
    const double R = 0.012, pi = std::acos(-1.0);
    double solid = 0.0;
    for (int p = 0; p < 3; ++p) {
      const Vec3 c{0.025 * (p + 1), 0.1 + 0.015 * std::sin(2.0 * pi * t / 0.1 + 2.0 * p), x.z};
      const double r2 = (x.x - c.x) * (x.x - c.x) + (x.y - c.y) * (x.y - c.y);
      if (r2 < R * R) solid += 0.5 * (1.0 - r2 / (R * R));
    }
    return 1.0 - solid;
  };
  CouplingFields& cf = s.couplingFields();
  const CartesianGrid& g = cf.voidFraction.grid();
  auto setVoidFraction = [&](Field& eps, double t) {
    for (int y = 0; y < g.cells[1]; ++y)
      for (int x = 0; x < g.cells[0]; ++x) eps(x, y, 0) = voidFraction(g.cellCentre(x, y, 0), t);
  };
  setVoidFraction(cf.voidFraction, 0.0);
  cf.voidFractionOld = cf.voidFraction;
  RunState state;
  state.fluid = &s;
  Params pw = Params::loadString("phase: water\n", "m.yaml"), pa = Params::loadString("phase: air\n", "m.yaml");
  auto water = Registry<Monitor>::instance().createByName("phase_mass", pw);
  auto air = Registry<Monitor>::instance().createByName("phase_mass", pa);
  const double w0 = water->sample(state)[0];
  air->sample(state);
  const double dt = 5e-4;
  Field older = cf.voidFraction;
  double worstWater = 0.0, worstAir = 0.0, extrapolation = 0.0, boundExcess = 0.0;
  for (int n = 0; n < 200; ++n) {
    older = cf.voidFractionOld;
    cf.voidFractionOld = cf.voidFraction;
    setVoidFraction(cf.voidFraction, (n + 1) * dt);
    s.step(dt);
    const auto w = water->sample(state), a = air->sample(state);
    worstWater = std::max(worstWater, std::abs(w[3]));
    worstAir = std::max(worstAir, std::abs(a[3]));
    for (int y = 0; y < g.cells[1]; ++y)
      for (int x = 0; x < 19; ++x)  // (the open cells)
        extrapolation += 1000.0 * g.cellVolume() * s.phaseFraction(1)(x, y, 0) *
                         (cf.voidFraction(x, y, 0) - 2.0 * cf.voidFractionOld(x, y, 0) + older(x, y, 0)) / w0;
    const auto range = vof::fractionRange(s.phaseFraction(1));
    boundExcess = std::max({boundExcess, -range[0], range[1] - 1.0});
  }
  std::printf("moving particles: water out %.3e of %.3e kg; worst balance %.2e (water), %.2e (air); "
              "extrapolation %.2e; bound excess %.1e\n",
              1000.0 * s.phaseOutflowVolume(1), w0, worstWater, worstAir, extrapolation, boundExcess);
  EXPECT_GT(s.phaseOutflowVolume(1), 0.01 * w0 / 1000.0);  // the slot drains
  EXPECT_LT(worstWater, 1e-6);
  EXPECT_LT(worstAir, 1e-6);
  EXPECT_LT(boundExcess, 1e-12);
}

// Every cases/vof_*.yaml runs shortened (vof_dam_break.yaml, vof_hydrostatic_tank.yaml,
// vof_tank_drain_2d.yaml, vof_hydrostatic_packed_bed.yaml, vof_bed_drain.yaml, vof_tank_drain.yaml):
// those without particles through the solver (a few steps, monitors finite), those with particles
// through `grainflow run`.
TEST(VofStep, ExampleCasesRunShortened) {
  int found = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(GRAINFLOW_SOURCE_DIR) + "/cases")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("vof_", 0) != 0 || entry.path().extension() != ".yaml") continue;
    ++found;
    SCOPED_TRACE(name);
    Params root = Params::loadFile(entry.path().string());
    if (root.has("insertion")) {
      const std::string out = ::testing::TempDir() + "/vof_case_" + std::to_string(found);
      const std::string cmd = std::string(GRAINFLOW_BINARY) + " run " + entry.path().string() +
                              " --quiet --threads 1 --overwrite --end-time 0.02 --output " + out + " > /dev/null 2>&1";
      EXPECT_EQ(std::system(cmd.c_str()), 0);
      EXPECT_TRUE(std::filesystem::exists(out + "/water_mass.csv"));
      continue;
    }
    const Domain domain = Domain::read(root);
    Solver s(root, domain, root.vec3({"gravity", "m/s^2", "gravity"}, Vec3{}));
    ASSERT_TRUE(s.vofEnabled());
    RunState state;
    state.fluid = &s;
    std::vector<std::unique_ptr<Monitor>> monitors;
    for (Params& m : root.list({"monitors", "-", "monitors"}))
      monitors.push_back(Registry<Monitor>::instance().create(m, {"type", "-", "monitor"}));
    for (int n = 0; n < 5; ++n) {
      s.step(2e-4);
      s.checkHealth(n, s.time());
      for (auto& m : monitors)
        for (double v : m->sample(state)) EXPECT_TRUE(std::isfinite(v));
    }
  }
  EXPECT_GE(found, 4);
}

// Bad input names the key and what was expected.
TEST(VofStep, CaseFileErrors) {
  auto message = [](const std::string& vof) {
    try {
      makeCase("domain: {min: [0, 0, 0], max: [1, 1, 1]}\nfluid:\n  cells: [4, 4, 4]\n  vof:\n" + vof);
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("    phases:\n      - {name: water, density: 1000, viscosity: 1e-3}\n").find("at least two phases"),
            std::string::npos);
  const std::string two = "    phases:\n      - {name: air, density: 1.2, viscosity: 1.8e-5}\n"
                          "      - {name: water, density: 1000, viscosity: 1e-3}\n";
  const std::string bad = message(two + "    regions:\n      - {phase: oil, min: [0, 0, 0], max: [1, 1, 1]}\n");
  EXPECT_NE(bad.find("oil"), std::string::npos) << bad;
  EXPECT_NE(bad.find("air, water"), std::string::npos) << bad;
  EXPECT_NE(bad.find("regions"), std::string::npos) << bad;
  EXPECT_NE(message("    phases:\n      - {name: a, density: 1, viscosity: 0}\n      - {name: a, density: 2, viscosity: 0}\n")
                .find("used twice"),
            std::string::npos);
  EXPECT_NE(message(two + "    courant: 1.5\n").find("courant"), std::string::npos);
}

}  // namespace
}  // namespace gf::fluid
