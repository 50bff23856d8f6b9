// An inlet per phase (fluid.boundaries.<side>.phase with fluid.vof; src/fluid/vof_step.cpp,
// docs/vof.md): what enters through a side carries that side's phase, each phase's volume closes
// with its own inflow and outflow, and a phase on a side that lets nothing in is an error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.hpp"
#include "fluid/solver.hpp"
#include "fluid_test_util.hpp"
#include "parallel/reductions.hpp"
#include "vof/vof.hpp"

namespace gf::fluid {
namespace {

using test::makeCase;

/// A 2D box 0.1 m x 0.1 m of air, no gravity: water enters through x_min and oil through x_max,
/// both at 0.1 m/s, and the mixture leaves through the pressure outlet on top.
std::string twoInletCase(const std::string& xMinPhase, const std::string& xMaxPhase) {
  return "domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.005]}\n"
         "fluid:\n"
         "  cells: [20, 20, 1]\n"
         "  pressure: {tolerance: 1.0e-12}\n"
         "  vof:\n"
         "    phases:\n"
         "      - {name: air, density: 1.0, viscosity: 1.8e-5}\n"
         "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
         "      - {name: oil, density: 800.0, viscosity: 5.0e-2}\n"
         "  boundaries:\n"
         "    x_min: {type: inlet, velocity: [0.1, 0, 0], ramp_time: 0.01" + xMinPhase + "}\n"
         "    x_max: {type: inlet, velocity: [-0.1, 0, 0], ramp_time: 0.01" + xMaxPhase + "}\n"
         "    y_max: {type: pressure_outlet, pressure: 0.0}\n";
}

// Water through x_min, oil through x_max, ramped up over 0.01 s, for 0.2 s (each front 0.02 m in). Each side lets in only
// its own phase: the first cells next to x_min hold water and no oil, those next to x_max oil and no
// water. What came in (the outflow monitor counts inflow negative) equals what is in the box plus
// what left through the top, per phase, to round-off; the fractions add up to 1.
TEST(VofInlets, EachInletLetsInItsOwnPhase) {
  auto c = makeCase(twoInletCase(", phase: water", ", phase: oil"));
  Solver& s = *c.solver;
  const parallel::RankReductionScope ranks(s.decomposition());
  ASSERT_EQ(s.phaseCount(), 3);
  const Field& eps = s.couplingFields().voidFraction;
  const double dt = 1e-3;
  const int steps = 200;
  for (int n = 0; n < steps; ++n) s.step(dt);
  // U H depth (t - T/2): the inlets' volume over the run with the linear ramp over T = 0.01 s, m^3
  const double inflowEach = 0.1 * 0.1 * 0.005 * (dt * steps - 0.5 * 0.01);
  const double air0 = 0.1 * 0.1 * 0.005;
  for (int i = 0; i < 3; ++i) {
    const double volume = vof::phaseVolume(s.phaseFraction(i), eps);
    const double initial = i == 0 ? air0 : 0.0;
    std::printf("phase %d: volume %.6e m^3, net outflow %.6e m^3, balance %.2e of the box\n", i, volume,
                s.phaseOutflowVolume(i), (volume + s.phaseOutflowVolume(i) - initial) / air0);
    EXPECT_NEAR(volume + s.phaseOutflowVolume(i), initial, 1e-12 * air0) << "phase " << i;
  }
  // The liquids came in, each its inlet's volume less what already left through the top's corners.
  for (int i = 1; i < 3; ++i) {
    EXPECT_GT(vof::phaseVolume(s.phaseFraction(i), eps), 0.95 * inflowEach) << "phase " << i;
    EXPECT_LT(s.phaseOutflowVolume(i), -0.95 * inflowEach) << "phase " << i;
    EXPECT_GT(s.phaseOutflowVolume(i), -1.0 * inflowEach) << "phase " << i;
  }
  // The first cells fill with their inlet's phase (upwind at a Courant number of 0.02 per step:
  // 1 - 0.98^n of the cell after n steps, 0.96 here) and hold none of the other side's.
  for (int j = 0; j < 10; ++j) {
    EXPECT_GT(s.phaseFraction(1)(0, j, 0), 0.9) << "row " << j;
    EXPECT_EQ(s.phaseFraction(2)(0, j, 0), 0.0) << "row " << j;
    EXPECT_GT(s.phaseFraction(2)(19, j, 0), 0.9) << "row " << j;
    EXPECT_EQ(s.phaseFraction(1)(19, j, 0), 0.0) << "row " << j;
  }
  double worstSum = 0.0;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i)
      worstSum = std::max(worstSum, std::abs(s.phaseFraction(0)(i, j, 0) + s.phaseFraction(1)(i, j, 0) +
                                             s.phaseFraction(2)(i, j, 0) - 1.0));
  EXPECT_LT(worstSum, 1e-12);
}

// Without a side's phase the inflow phase of fluid.vof enters there (the first phase by default):
// air through both sides, the liquids stay out.
TEST(VofInlets, SidesWithoutAPhaseTakeTheInflowPhase) {
  auto c = makeCase(twoInletCase("", ""));
  Solver& s = *c.solver;
  const parallel::RankReductionScope ranks(s.decomposition());
  for (int n = 0; n < 20; ++n) s.step(1e-3);
  const Field& eps = s.couplingFields().voidFraction;
  EXPECT_EQ(vof::phaseVolume(s.phaseFraction(1), eps), 0.0);
  EXPECT_EQ(vof::phaseVolume(s.phaseFraction(2), eps), 0.0);
  // (the air's balance closes while the ramp changes the inlets' velocity: the transport takes the
  // last projection's inlet fluxes)
  const double air0 = 0.1 * 0.1 * 0.005;
  EXPECT_NEAR(vof::phaseVolume(s.phaseFraction(0), eps) + s.phaseOutflowVolume(0), air0, 1e-12 * air0);
}

// A phase on a wall, an unknown phase, and a phase without fluid.vof: the message names the key,
// what was found and what was expected.
TEST(VofInlets, CaseFileErrors) {
  auto message = [](const std::string& yaml) {
    try {
      makeCase(yaml);
    } catch (const CaseError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string wall = twoInletCase(", phase: water", ", phase: oil");
  wall += "    y_min: {type: wall, phase: water}\n";
  const std::string onWall = message(wall);
  EXPECT_NE(onWall.find("phase"), std::string::npos) << onWall;
  EXPECT_NE(onWall.find("closed or periodic"), std::string::npos) << onWall;
  const std::string unknown = message(twoInletCase(", phase: slag", ""));
  EXPECT_NE(unknown.find("slag"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("air, water, oil"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("x_min"), std::string::npos) << unknown;
  const std::string noVof = message(
      "domain: {min: [0, 0, 0], max: [1, 1, 1]}\nfluid:\n  cells: [4, 4, 4]\n  boundaries:\n"
      "    x_min: {type: inlet, velocity: [1, 0, 0], phase: water}\n    x_max: {type: pressure_outlet}\n");
  EXPECT_NE(noVof.find("fluid.vof"), std::string::npos) << noVof;
}

}  // namespace
}  // namespace gf::fluid
