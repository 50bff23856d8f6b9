// The fluid solver on a grid split among MPI ranks (Solver with a parallel::Decomposition): each
// rank steps its box of cells, exchanging ghost layers with its neighbours, with the pressure
// through hypre and the Krylov reductions as allreduces. ctest runs this under mpirun -n 2 and
// -n 4 with every layout of that rank count; each rank also runs the whole grid alone (a solver
// without decomposition, hypre on its own process) and compares its box with it, point by point:
// velocity, pressure and scalar agree to 1e-10 of the largest value after the steps (the solvers'
// tolerances are tight, so only round-off in the order of the reductions separates the runs).
// Cases: the lid-driven cavity (3D, two pressure correctors), a periodic channel at a prescribed
// flow rate with a blocked box, a parabolic inlet to a pressure outlet with a passive scalar, and
// the volume-averaged equations with a void fraction, drag coefficient and force density varying
// in space (superficial inlet, outflow). The coupling's cell fields with their ghosts across the
// cuts and the monitors' samples (kinetic energy, plane means, flow rates through planes on and
// off the cuts, probes, line profiles) agree as well. Checkpoints hold the whole grid: written on
// any layout, they restart the whole grid and the other way round; the multigrid asked for on
// several ranks runs as hypre. On one process the decomposition has one rank: the solver is the
// single-process one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fluid/sampling.hpp"
#include "fluid_test_util.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/environment.hpp"
#include "parallel/exchange.hpp"

namespace gf::fluid {
namespace {

using parallel::Decomposition;
using parallel::Layout;

/// Layouts of the rank count of this run (one rank: the whole grid).
std::vector<Layout> layoutsFor(int ranks) {
  if (ranks == 2) return {{2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
  if (ranks == 4) return {{2, 2, 1}, {1, 2, 2}, {2, 1, 2}, {4, 1, 1}};
  return {{ranks, 1, 1}};
}

/// The coupling fields of the void-fraction case, as functions of position (both runs alike).
void setCoupling(Solver& s, double t) {
  CouplingFields& cf = s.couplingFields();
  const CartesianGrid& g = s.grid();
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        const Vec3 x = g.cellCentre(i, j, k);
        const double wave = std::sin(2.0 * x.x + 3.0 * x.y - t) * std::cos(2.5 * x.z);
        cf.voidFractionOld(i, j, k) = cf.voidFraction(i, j, k);
        cf.voidFraction(i, j, k) = 0.7 + 0.2 * wave;
        cf.dragCoefficient(i, j, k) = 50.0 * (1.0 + wave * wave);
        cf.forceDensity[0](i, j, k) = 20.0 * wave;
        cf.forceDensity[1](i, j, k) = -5.0 * x.x;
        cf.forceDensity[2](i, j, k) = 0.0;
        cf.particleVelocity[0](i, j, k) = 0.1 * wave;
        cf.particleVelocity[1](i, j, k) = 0.05;
        cf.particleVelocity[2](i, j, k) = 0.0;
      }
}

double maxAbs(const Field& f) {
  double m = 0.0;
  const auto& pts = f.points();
  for (int k = 0; k < pts[2]; ++k)
    for (int j = 0; j < pts[1]; ++j)
      for (int i = 0; i < pts[0]; ++i) m = std::max(m, std::abs(f(i, j, k)));
  return m;
}

double velocityScale(const Solver& s) {
  return std::max({maxAbs(s.velocity(0)), maxAbs(s.velocity(1)), maxAbs(s.velocity(2))});
}

/// Largest |local - whole| over this rank's interior points (its box of the whole grid's points),
/// relative to the largest |whole|.
double relativeDifference(const Field& local, const Field& whole, const std::array<int, 3>& offset) {
  double m = 0.0;
  const auto& pts = local.points();
  for (int k = 0; k < pts[2]; ++k)
    for (int j = 0; j < pts[1]; ++j)
      for (int i = 0; i < pts[0]; ++i)
        m = std::max(m, std::abs(local(i, j, k) - whole(offset[0] + i, offset[1] + j, offset[2] + k)));
  const double scale = maxAbs(whole);
  return scale > 0.0 ? m / scale : m;
}

/// Steps the case on this rank's box of each layout and alone on the whole grid; checks they agree.
void compareDecomposed(const std::string& yaml, int steps, double dt, bool coupled) {
  const parallel::Environment& env = parallel::Environment::instance();
  const std::string tight = "  momentum_tolerance: 1.0e-13\n  momentum_max_iterations: 400\n"
                            "  pressure: {solver: hypre, tolerance: 1.0e-13, max_iterations: 500}\n";
  const std::string text = yaml + tight;
  auto whole = test::makeCase(text);
  for (int n = 0; n < steps; ++n) {
    if (coupled) setCoupling(*whole.solver, n * dt);
    whole.solver->step(dt);
  }
  for (const Layout& layout : layoutsFor(env.size())) {
    Params params = Params::loadString(text, "test.yaml");
    const Domain domain = Domain::read(params);
    const Decomposition layoutOnly(domain, layout, env.size(), env.rank());  // (the solver adds the grid's cuts)
    Solver solver(params, domain, Vec3{}, layoutOnly);
    const Decomposition& d = solver.decomposition();
    ASSERT_EQ(d.layout(), layout);
    for (int n = 0; n < steps; ++n) {
      if (coupled) setCoupling(solver, n * dt);
      solver.step(dt);
    }
    const auto offset = d.cellOffset();
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double diff = relativeDifference(solver.velocity(c), whole.solver->velocity(c), offset);
      EXPECT_LT(diff, 1e-10) << "velocity " << c << ", rank " << env.rank() << " of layout " << d.describe();
      worst = std::max(worst, diff);
    }
    const double pdiff = relativeDifference(solver.pressure(), whole.solver->pressure(), offset);
    EXPECT_LT(pdiff, 1e-10) << "pressure, rank " << env.rank() << " of layout " << d.describe();
    if (solver.hasScalar()) {
      EXPECT_LT(relativeDifference(solver.scalar(), whole.solver->scalar(), offset), 1e-10)
          << "scalar, rank " << env.rank() << " of layout " << d.describe();
    }
    EXPECT_NEAR(solver.drivingPressureGradient(), whole.solver->drivingPressureGradient(),
                1e-10 * std::max(1.0, std::abs(whole.solver->drivingPressureGradient())));
    // The time step estimate and the divergence are global maxima: the same on every rank.
    EXPECT_NEAR(solver.stableTimeStep(), whole.solver->stableTimeStep(), 1e-10 * whole.solver->stableTimeStep());
    EXPECT_NEAR(solver.maxDivergence(), whole.solver->maxDivergence(), 1e-8 * velocityScale(*whole.solver));
    // The coupling's cell fields, ghosts left to their readers: the ghosts across the cuts hold
    // the neighbours' cells (every point with a global index inside the domain).
    {
      Field cv[3], cw[3], gv[3], gw[3];
      solver.cellVelocity(cv, CellGhosts::Left);
      whole.solver->cellVelocity(cw);
      solver.pressureGradient(gv, CellGhosts::Left);
      whole.solver->pressureGradient(gw);
      const int g = solver.grid().ghosts;
      const auto& n = solver.grid().cells;
      const auto& N = whole.solver->grid().cells;
      double m = 0.0;
      for (int k = -g; k < n[2] + g; ++k)
        for (int j = -g; j < n[1] + g; ++j)
          for (int i = -g; i < n[0] + g; ++i) {
            const int I = offset[0] + i, J = offset[1] + j, K = offset[2] + k;
            if (I < 0 || J < 0 || K < 0 || I >= N[0] || J >= N[1] || K >= N[2]) continue;
            for (int c = 0; c < 3; ++c) {
              m = std::max(m, std::abs(cv[c](i, j, k) - cw[c](I, J, K)) / std::max(1e-300, velocityScale(*whole.solver)));
              m = std::max(m, std::abs(gv[c](i, j, k) - gw[c](I, J, K)) / std::max({1e-300, maxAbs(gw[0]), maxAbs(gw[1]), maxAbs(gw[2])}));
            }
          }
      EXPECT_LT(m, 1e-9) << "cell velocity and pressure gradient with their ghosts, layout " << d.describe();
    }
    // The monitors' samples (collective): the whole domain's values on every rank.
    const Solver& w = *whole.solver;
    const Domain& dom = domain;
    auto expectSame = [&](double got, double want, double scale, const char* what) {
      EXPECT_NEAR(got, want, 1e-10 * std::max(scale, std::abs(want))) << what << ", layout " << d.describe();
    };
    expectSame(kineticEnergy(solver), kineticEnergy(w), 0.0, "kinetic energy");
    const double pScale = maxAbs(w.pressure()), uScale = velocityScale(w);
    for (int a = 0; a < 3; ++a) {
      const double length = dom.max[a] - dom.min[a];
      for (double at : {0.0, 0.41, 0.5, 1.0}) {
        const double x = dom.min[a] + at * length;
        expectSame(planeMeanPressure(solver, a, x), planeMeanPressure(w, a, x), pScale, "plane mean pressure");
        expectSame(flowRate(solver, a, x), flowRate(w, a, x), uScale * length * length, "flow rate");
      }
      const Vec3 through{dom.min.x + 0.52 * (dom.max.x - dom.min.x), dom.min.y + 0.47 * (dom.max.y - dom.min.y),
                         dom.min.z + 0.5 * (dom.max.z - dom.min.z)};
      const LineProfile got = lineProfile(solver, a, through), want = lineProfile(w, a, through);
      ASSERT_EQ(got.position.size(), want.position.size());
      for (std::size_t q = 0; q < want.position.size(); ++q) {
        for (int c = 0; c < 3; ++c) expectSame(got.velocity[q][c], want.velocity[q][c], uScale, "profile velocity");
        expectSame(got.pressure[q], want.pressure[q], pScale, "profile pressure");
        expectSame(got.voidFraction[q], want.voidFraction[q], 1.0, "profile void fraction");
      }
      const auto p = probe(solver, through), q = probe(w, through);
      for (int c = 0; c < 4; ++c) expectSame(p[c], q[c], c < 3 ? uScale : pScale, "probe");
    }
    if (env.rank() == 0)
      std::printf("layout %s: velocity %.1e, pressure %.1e of the largest value\n", d.describe().c_str(), worst, pdiff);
  }
}

TEST(DecomposedFluid, CheckpointsRestartOnAnyRankCount) {
  // A checkpoint holds the whole grid's arrays: written on the ranks of a layout (gathered on
  // rank 0), it restarts the whole grid alone, and the whole grid's checkpoint restarts each
  // rank's box; both continue as the run that never stopped (to 1e-10).
  const parallel::Environment& env = parallel::Environment::instance();
  const std::string text = "domain: {min: [0, 0, 0], max: [2, 1, 1], periodic: [1, 0, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.01\n  cells: [16, 12, 12]\n"
                           "  blocked: [{shape: box, min: [0.8, 0.3, 0.3], max: [1.2, 0.6, 0.7]}]\n"
                           "  driving: {mode: flow_rate, axis: x, bulk_velocity: 1.0}\n"
                           "  initial: {velocity: [1, 0.1, 0.05]}\n"
                           "  momentum_tolerance: 1.0e-13\n  momentum_max_iterations: 400\n"
                           "  pressure: {solver: hypre, tolerance: 1.0e-13, max_iterations: 500}\n";
  const double dt = 0.02;
  auto whole = test::makeCase(text);
  for (int n = 0; n < 3; ++n) whole.solver->step(dt);
  BinaryWriter wholeCheckpoint;
  whole.solver->save(wholeCheckpoint);
  for (const Layout& layout : layoutsFor(env.size())) {
    Params params = Params::loadString(text, "test.yaml");
    const Domain domain = Domain::read(params);
    Solver split(params, domain, Vec3{}, Decomposition(domain, layout, env.size(), env.rank()));
    for (int n = 0; n < 3; ++n) split.step(dt);
    BinaryWriter out;
    split.save(out);
    const parallel::Bytes bytes = env.size() > 1 ? parallel::broadcastFromRoot(out.bytes()) : out.bytes();
    ASSERT_EQ(bytes.size(), wholeCheckpoint.bytes().size()) << "the whole grid's arrays, layout " << split.decomposition().describe();
    // The whole grid restarted from the split run's checkpoint, the split run from the whole grid's.
    auto alone = test::makeCase(text);
    BinaryReader in(bytes.data(), bytes.size());
    alone.solver->load(in);
    Params params2 = Params::loadString(text, "test.yaml");
    Solver restarted(params2, domain, Vec3{}, Decomposition(domain, layout, env.size(), env.rank()));
    BinaryReader in2(wholeCheckpoint.bytes().data(), wholeCheckpoint.bytes().size());
    restarted.load(in2);
    auto continued = test::makeCase(text);
    BinaryReader in3(wholeCheckpoint.bytes().data(), wholeCheckpoint.bytes().size());
    continued.solver->load(in3);
    for (int n = 0; n < 3; ++n) {
      alone.solver->step(dt);
      restarted.step(dt);
      continued.solver->step(dt);
    }
    const auto offset = restarted.decomposition().cellOffset();
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(relativeDifference(alone.solver->velocity(c), continued.solver->velocity(c), {0, 0, 0}), 1e-10) << c;
      EXPECT_LT(relativeDifference(restarted.velocity(c), continued.solver->velocity(c), offset), 1e-10) << c;
    }
    EXPECT_LT(relativeDifference(alone.solver->pressure(), continued.solver->pressure(), {0, 0, 0}), 1e-10);
    EXPECT_LT(relativeDifference(restarted.pressure(), continued.solver->pressure(), offset), 1e-10);
  }
}

TEST(DecomposedFluid, MultigridOnSeveralRanksIsGatheredOrGoesThroughHypre) {
  // fluid.pressure.solver: multigrid (the default) on a decomposed grid: a grid of at most
  // fluid.pressure.gather_cells cells is gathered onto rank 0 and solved there by the multigrid
  // (fluid/gathered_pressure.hpp), so the run matches the whole grid's multigrid run; with
  // gather_cells below the grid's 1,728 cells the pressure goes through hypre and the run matches
  // the whole grid solved by hypre.
  const parallel::Environment& env = parallel::Environment::instance();
  const std::string base = "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.01\n  cells: [12, 12, 12]\n"
                           "  boundaries:\n    y_max: {type: wall, velocity: [1, 0, 0]}\n"
                           "  momentum_tolerance: 1.0e-13\n";
  for (const bool gathered : {true, false}) {
    auto whole = test::makeCase(base + (gathered ? "  pressure: {solver: multigrid, tolerance: 1.0e-13}\n"
                                                 : "  pressure: {solver: hypre, tolerance: 1.0e-13}\n"));
    for (int n = 0; n < 3; ++n) whole.solver->step(0.02);
    const std::string text = base + (gathered ? "  pressure: {solver: multigrid, tolerance: 1.0e-13}\n"
                                              : "  pressure: {solver: multigrid, tolerance: 1.0e-13, gather_cells: 1000}\n");
    Params params = Params::loadString(text, "test.yaml");
    const Domain domain = Domain::read(params);
    Solver split(params, domain, Vec3{}, Decomposition(domain, layoutsFor(env.size()).front(), env.size(), env.rank()));
    for (int n = 0; n < 3; ++n) split.step(0.02);
    const auto offset = split.decomposition().cellOffset();
    // (one rank, gather_cells exceeded: the multigrid against hypre, to their tolerance)
    const double tol = env.size() > 1 || gathered ? 1e-10 : 1e-8;
    for (int c = 0; c < 3; ++c)
      EXPECT_LT(relativeDifference(split.velocity(c), whole.solver->velocity(c), offset), tol) << c << " " << gathered;
    if (env.size() > 1 || gathered) {
      EXPECT_LT(relativeDifference(split.pressure(), whole.solver->pressure(), offset), tol);
    }
  }
}

TEST(DecomposedFluid, CavityMatchesTheWholeGrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.01\n  cells: [12, 12, 12]\n  correctors: 2\n"
                           "  boundaries:\n    y_max: {type: wall, velocity: [1, 0, 0.3]}\n";
  compareDecomposed(yaml, 6, 0.02, false);
}

TEST(DecomposedFluid, PeriodicChannelAtAFlowRateMatchesTheWholeGrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [2, 1, 1], periodic: [1, 0, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.01\n  cells: [16, 12, 12]\n  model: B\n"
                           "  blocked: [{shape: box, min: [0.8, 0.3, 0.3], max: [1.2, 0.6, 0.7]}]\n"
                           "  driving: {mode: flow_rate, axis: x, bulk_velocity: 1.0}\n"
                           "  initial: {velocity: [1, 0.1, 0.05]}\n";
  compareDecomposed(yaml, 6, 0.02, false);
}

TEST(DecomposedFluid, InletToPressureOutletMatchesTheWholeGrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [3, 1, 1]}\n"
                           "fluid:\n  density: 1\n  viscosity: 0.02\n  cells: [16, 12, 12]\n  convection: central\n"
                           "  blocked: [{shape: box, min: [1, 0.25, 0.25], max: [1.5, 0.75, 0.75]}]\n"
                           "  boundaries:\n"
                           "    x_min: {type: inlet, velocity: [1, 0, 0], profile: parabolic, scalar: fixed, scalar_value: 1}\n"
                           "    x_max: {type: pressure_outlet, pressure: 0}\n"
                           "  scalar: {enabled: true, diffusivity: 0.01}\n";
  compareDecomposed(yaml, 6, 0.02, false);
}

TEST(DecomposedFluid, VoidFractionDragAndForceMatchTheWholeGrid) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [1, 2, 1], periodic: [1, 0, 0]}\n"
                           "fluid:\n  density: 1000\n  viscosity: 0.001\n  cells: [12, 16, 12]\n"
                           "  boundaries:\n    y_min: {type: inlet, velocity: [0, 0.1, 0]}\n"
                           "    y_max: {type: outflow}\n";
  compareDecomposed(yaml, 6, 0.01, true);
}

}  // namespace
}  // namespace gf::fluid
