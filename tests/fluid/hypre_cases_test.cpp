// Whole runs with fluid.pressure.solver: hypre against the default multigrid: the same steps give
// the same fields to the solvers' tolerance (1e-10 here, so the fields agree to ~1e-7 after the
// differences of several steps add up).
//  - the lid-driven cavity (walls only: the singular Neumann problem and its gauge);
//  - a periodic channel driven at a flow rate (periodic sides, singular);
//  - a channel from an inlet to a pressure outlet (Dirichlet side) with a blocked box;
//  - the bubbling fluidised bed (cases/cfddem_bubbling_fluidised_bed.yaml), a few coupling steps:
//    the pressure system with the void fraction of 24750 particles and the pressure outlet.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "app/simulation.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

double maxAbsInterior(const Field& f, const Field* other = nullptr) {
  double m = 0.0;
  const auto& pts = f.points();
  for (int k = 0; k < pts[2]; ++k)
    for (int j = 0; j < pts[1]; ++j)
      for (int i = 0; i < pts[0]; ++i) m = std::max(m, std::abs(f(i, j, k) - (other ? (*other)(i, j, k) : 0.0)));
  return m;
}

/// Runs `steps` steps of the case text with each solver; returns the largest difference of a
/// velocity component relative to the largest velocity component.
double compareRuns(const std::string& yaml, const std::string& pressureKeys, int steps, double dt) {
  auto withSolver = [&](const std::string& solver) {
    return yaml + "  pressure: {solver: " + solver + ", " + pressureKeys + "}\n";
  };
  auto m = test::makeCase(withSolver("multigrid"));
  auto h = test::makeCase(withSolver("hypre"));
  for (int n = 0; n < steps; ++n) {
    m.solver->step(dt);
    h.solver->step(dt);
    EXPECT_TRUE(h.solver->lastStep().pressureResidual <= 1e-10) << "step " << n;
  }
  double worst = 0.0, scale = 0.0;
  for (int c = 0; c < 3; ++c) {
    scale = std::max(scale, maxAbsInterior(m.solver->velocity(c)));
    worst = std::max(worst, maxAbsInterior(h.solver->velocity(c), &m.solver->velocity(c)));
  }
  worst /= scale;
  std::printf("%d steps: max velocity difference %.2e of the largest value\n", steps, worst);
  return worst;
}

TEST(HypreCases, CavityMatchesMultigrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [1, 1, 0.1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.01\n  cells: [32, 32, 1]\n  convection: central\n"
                           "  boundaries:\n    y_max: {type: wall, velocity: [1, 0, 0]}\n";
  EXPECT_LT(compareRuns(yaml, "tolerance: 1e-10", 40, 0.5 / 32), 1e-7);
}

TEST(HypreCases, PeriodicChannelMatchesMultigrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [4, 1, 1], periodic: [1, 0, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.01\n  cells: [24, 16, 6]\n  model: B\n"
                           "  driving: {mode: flow_rate, axis: x, bulk_velocity: 1.0}\n"
                           "  initial: {velocity: [1, 0.1, 0.05]}\n";
  EXPECT_LT(compareRuns(yaml, "tolerance: 1e-10", 20, 0.02), 1e-7);
}

TEST(HypreCases, InletToPressureOutletMatchesMultigrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [3, 1, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.02\n  cells: [24, 8, 8]\n"
                           "  blocked: [{shape: box, min: [1, 0.25, 0.25], max: [1.5, 0.75, 0.75]}]\n"
                           "  boundaries:\n    x_min: {type: inlet, velocity: [1, 0, 0]}\n"
                           "    x_max: {type: pressure_outlet, pressure: 0}\n";
  EXPECT_LT(compareRuns(yaml, "tolerance: 1e-10", 20, 0.02), 1e-7);
}

TEST(HypreCases, BubblingBedPressureMatchesMultigrid) {
  const std::string file = std::string(GRAINFLOW_SOURCE_DIR) + "/cases/cfddem_bubbling_fluidised_bed.yaml";
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  const std::string base = text.str();
  const std::size_t at = base.find("\nfluid:\n");
  ASSERT_NE(at, std::string::npos);
  auto withSolver = [&](const std::string& solver) {
    std::string yaml = base;
    yaml.insert(at + 8, "  pressure: {solver: " + solver + ", tolerance: 1.0e-10}\n");
    return yaml;
  };
  const int steps = 4;
  Field pressure[2];
  double seconds[2] = {0.0, 0.0};  // pressure phase of steps 2.. (the first includes hypre's and MPI's start)
  int iterations[2] = {0, 0};
  for (int s = 0; s < 2; ++s) {
    Params root = Params::loadString(withSolver(s == 0 ? "multigrid" : "hypre"), file);
    app::RunOptions options;
    options.quiet = true;
    app::Simulation sim(root, file, options);
    double first = 0.0;
    for (int n = 0; n < steps; ++n) {
      sim.advance();
      EXPECT_LE(sim.fluid()->lastStep().pressureResidual, 1e-10);
      iterations[s] += sim.fluid()->lastStep().pressureIterations;
      if (n == 0) first = sim.fluid()->timers().seconds(Phase::PressureSolve);
    }
    seconds[s] = (sim.fluid()->timers().seconds(Phase::PressureSolve) - first) / (steps - 1);
    pressure[s] = sim.fluid()->pressure();
  }
  // The pressure relative to its outlet value (0): the bed's weight, ~ 1e3 Pa at the bottom.
  const double scale = maxAbsInterior(pressure[0]);
  const double difference = maxAbsInterior(pressure[1], &pressure[0]) / scale;
  std::printf("bubbling bed, %d coupling steps: pressure difference %.2e of max |p| = %.4g Pa; pressure solve "
              "multigrid %.4f s per step (%d iterations in all), hypre %.4f s per step (%d iterations)\n",
              steps, difference, scale, seconds[0], iterations[0], seconds[1], iterations[1]);
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(difference, 1e-8);
}

}  // namespace
}  // namespace gf::fluid
