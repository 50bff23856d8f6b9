// Thread teams of small coupled grids (fluid/momentum_team.cpp, MultigridPoisson::solveMgpcg):
// the results must not depend on the thread count (the TeamTuner switches between one thread and
// the team at run time), and the projection must still meet continuity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include <omp.h>

#include "fluid/team_tuner.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

// The 2 x 30 x 90 grid of cases/cfddem_bubbling_fluidised_bed.yaml (5400 cells: a team of 2 on
// two threads) with a packed bed (eps = 0.45, Ergun drag) and a rising bubble (eps = 1), as
// bench/fluid_solver.cpp's BM_FluidBedStep.
const char* kBedCase =
    "domain: {min: [0, 0, 0], max: [0.015, 0.15, 0.45]}\nfluid:\n  density: 1.2\n  viscosity: 1.8e-5\n"
    "  cells: [2, 30, 90]\n  boundaries:\n    x_min: {type: slip}\n    x_max: {type: slip}\n"
    "    z_min: {type: inlet, velocity: [0, 0, 1.875]}\n    z_max: {type: pressure_outlet}\n";

void setBedFields(Solver& solver, double zb) {
  CouplingFields& cf = solver.couplingFields();
  const CartesianGrid& g = solver.grid();
  cf.voidFractionOld = cf.voidFraction;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        const Vec3 x = g.cellCentre(i, j, k);
        const double r2 = (x.y - 0.075) * (x.y - 0.075) + (x.z - zb) * (x.z - zb);
        const double eps = (x.z < 0.15 && r2 > 0.025 * 0.025) ? 0.45 : 1.0;
        const double es = 1.0 - eps, d = 2.5e-3;
        cf.voidFraction(i, j, k) = eps;
        // Ergun (Gidaspow dense branch) at |u - v| = 1.875 m/s.
        cf.dragCoefficient(i, j, k) =
            eps < 1.0 ? 150.0 * es * es * 1.8e-5 / (eps * d * d) + 1.75 * es * 1.2 * 1.875 / d : 0.0;
      }
}

struct BedRun {
  std::vector<double> u[3], p;
  /// Cell velocity and pressure gradient (ghosts included) of 9 calls after the steps, one after
  /// the other: the coupling's reads, on one thread or the team (the tuner alternates).
  std::vector<double> cellVelocity, pressureGradient;
  double maxDivergence = 0.0;  // over all steps, 1/s
};

BedRun runBed(int threads, int steps, const char* yaml = kBedCase) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto c = test::makeCase(yaml, Vec3{0.0, 0.0, -9.81});
  Solver& s = *c.solver;
  const double dt = 2e-5;
  double zb = 0.06;
  setBedFields(s, zb);
  setBedFields(s, zb);
  BedRun run;
  for (int n = 0; n < steps; ++n) {
    zb += 2.0 * dt;  // the bubble rises at 2 m/s: eps changes every step
    setBedFields(s, zb);
    s.step(dt);
    run.maxDivergence = std::max(run.maxDivergence, s.maxDivergence());
  }
  for (int a = 0; a < 3; ++a) run.u[a] = s.velocity(a).data();
  run.p = s.pressure().data();
  for (int call = 0; call < 9; ++call) {
    Field v[3], g[3];
    s.cellVelocity(v);
    s.pressureGradient(g);
    for (int a = 0; a < 3; ++a) {
      run.cellVelocity.insert(run.cellVelocity.end(), v[a].data().begin(), v[a].data().end());
      run.pressureGradient.insert(run.pressureGradient.end(), g[a].data().begin(), g[a].data().end());
    }
  }
  omp_set_num_threads(saved);
  return run;
}

TEST(FluidTeam, BedStepsAreBitIdenticalForOneAndTwoThreads) {
  // 40 steps: the tuners alternate one thread and the team during their warm-up (4 calls each).
  const BedRun one = runBed(1, 40), two = runBed(2, 40);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(one.u[a], two.u[a]) << "velocity component " << a;
  EXPECT_EQ(one.p, two.p);
  EXPECT_EQ(one.cellVelocity, two.cellVelocity);
  EXPECT_EQ(one.pressureGradient, two.pressureGradient);
}

TEST(FluidTeam, OtherBoundariesAreBitIdenticalForOneAndTwoThreads) {
  // The members' ghost fills (fillAllGhosts, the projection's, cellVelocity, pressureGradient)
  // with the other boundary kinds: periodic x, a superficial inlet (reads eps ghosts) and a
  // pressure outlet on the y sides, a moving wall and an outflow on the z sides; 3600 cells: a
  // team of 2 on two threads.
  const char* yaml =
      "domain: {min: [0, 0, 0], max: [0.012, 0.15, 0.45], periodic: [1, 0, 0]}\nfluid:\n  density: 1.2\n"
      "  viscosity: 1.8e-5\n  cells: [4, 30, 30]\n  boundaries:\n"
      "    y_min: {type: inlet, velocity: [0, 0.5, 0]}\n    y_max: {type: pressure_outlet, pressure: 3}\n"
      "    z_min: {type: wall, velocity: [0.1, 0.2, 0]}\n    z_max: {type: outflow}\n";
  const BedRun one = runBed(1, 24, yaml), two = runBed(2, 24, yaml);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(one.u[a], two.u[a]) << "velocity component " << a;
  EXPECT_EQ(one.p, two.p);
  EXPECT_EQ(one.cellVelocity, two.cellVelocity);
  EXPECT_EQ(one.pressureGradient, two.pressureGradient);
}

TEST(FluidTeam, BedProjectionMeetsContinuity) {
  // max |div(eps u) + d eps/dt| after the projection, relative to the largest source term
  // |d eps/dt| = 0.55 / dt at the bubble edge: the pressure tolerance (1e-8) times a margin for
  // the cell-wise maximum (the solver's residual is a 2-norm; 4e-9 measured).
  const BedRun two = runBed(2, 40);
  EXPECT_LT(two.maxDivergence, 1e-7 * 0.55 / 2e-5);
}

}  // namespace
}  // namespace gf::fluid

namespace gf::fluid {
namespace {

TEST(TeamTuner, KeepsTheFasterChoiceAndProbesTheOther) {
  // Synthetic timings: the team takes 1 ms, one thread 3 ms (idle machine), then the team
  // becomes slow (20 ms: an oversubscribed machine) and the tuner must switch to one thread.
  if (TeamTuner::forcedChoice() != 0) GTEST_SKIP() << "GF_FLUID_TEAM overrides the tuner";
  TeamTuner tuner;
  auto simulate = [&](double teamSeconds, double serialSeconds, int calls) -> int {
    int teamCalls = 0;
    for (int n = 0; n < calls; ++n) {
      const int team = tuner.pick(2);
      EXPECT_TRUE(team == 1 || team == 2);
      tuner.record(team, team == 2 ? teamSeconds : serialSeconds);
      teamCalls += team == 2;
    }
    return teamCalls;
  };
  EXPECT_EQ(tuner.pick(1), 1);  // nothing to choose
  const int idleTeamCalls = simulate(1e-3, 3e-3, 1000);
  EXPECT_GT(idleTeamCalls, 960);  // warm-up (4 serial calls) and rare serial probes only
  const int busyTeamCalls = simulate(20e-3, 3e-3, 1000);
  EXPECT_LT(busyTeamCalls, 40);  // switched after a few calls, probes back off (64, 128, ...)
  EXPECT_GT(busyTeamCalls, 0);   // but still probes the team
}

TEST(TeamTuner, KeepsATeamThatIsOnlySlightlySlower) {
  // A team within kTeamTolerance (2) of one thread is kept (its measured time includes waking
  // the other threads after one-thread phases); a team 3 x slower is not.
  if (TeamTuner::forcedChoice() != 0) GTEST_SKIP() << "GF_FLUID_TEAM overrides the tuner";
  auto teamCallsOf = [](double teamSeconds, double serialSeconds) {
    TeamTuner tuner;
    int teamCalls = 0;
    for (int n = 0; n < 1000; ++n) {
      const int team = tuner.pick(2);
      tuner.record(team, team == 2 ? teamSeconds : serialSeconds);
      teamCalls += team == 2;
    }
    return teamCalls;
  };
  EXPECT_GT(teamCallsOf(1.5e-3, 1e-3), 960);
  EXPECT_LT(teamCallsOf(3e-3, 1e-3), 40);
}

}  // namespace
}  // namespace gf::fluid
