// Fluid benchmarks (run with OMP_NUM_THREADS=1 and =2):
//  - BM_FluidPressureSolve/n: MGPCG on the n^3 Poisson problem of a closed box (pure Neumann,
//    unit coefficients) from zero to a relative residual of 1e-8; counters: iterations,
//    seconds per solve, ns per cell per CG iteration.
//  - BM_FluidCavityStep/n: one full time step (convection, implicit viscous predictor,
//    projection) of the 3D lid-driven cavity at Re = 100, CFL 0.5; counter ns per cell per step.
//  - BM_FluidBedStep: one fluid step (dt = 2e-5 s) on the 2 x 30 x 90 grid of
//    cases/cfddem_bubbling_fluidised_bed.yaml (slip x walls, no-slip y walls, inlet 1.875 m/s,
//    pressure outlet) with a packed bed (eps = 0.45, Ergun drag K) in the lower third and a rising
//    bubble (eps = 1) in it; argument: pressure tolerance 1e-arg (6: the case file's, 8: the
//    solver default); counters: ns per cell per step (whole step and pressure solve), pressure
//    and momentum iterations, max divergence after the projection (1/s).
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "fluid/multigrid.hpp"
#include "fluid/solver.hpp"

namespace {

void BM_FluidPressureSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::array<int, 3> cells{n, n, n};
  std::array<std::vector<double>, 3> T;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = cells;
    fn[a] += 1;
    T[a].assign(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2], 0.0);
    for (int k = 0; k < fn[2]; ++k)
      for (int j = 0; j < fn[1]; ++j)
        for (int i = 0; i < fn[0]; ++i) {
          const int idx[3] = {i, j, k};
          if (idx[a] == 0 || idx[a] == n) continue;  // walls: Neumann
          T[a][i + static_cast<std::size_t>(fn[0]) * (j + static_cast<std::size_t>(fn[1]) * k)] = 1.0 / n;
        }
  }
  gf::fluid::MultigridPoisson mg;
  mg.setup(cells, {false, false, false}, T, {});
  const std::size_t N = static_cast<std::size_t>(n) * n * n;
  std::vector<double> b(N), x(N);
  for (std::size_t c = 0; c < N; ++c) b[c] = std::sin(0.37 * c) + 0.2 * std::cos(1.3 * c);
  int iterations = 0;
  for (auto _ : state) {
    std::fill(x.begin(), x.end(), 0.0);
    const auto r = mg.solve(x, b, 1e-8, 200);
    iterations = r.iterations;
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["iterations"] = iterations;
  state.counters["levels"] = mg.levels();
  state.counters["s_per_solve"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate |
                                                               benchmark::Counter::kInvert);
  state.counters["ns_per_cell_iter"] = benchmark::Counter(
      1e-9 * static_cast<double>(N) * iterations,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FluidPressureSolve)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FluidCavityStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string yaml = "domain: {min: [0, 0, 0], max: [1, 1, 1]}\nfluid:\n  density: 1\n  viscosity: 0.01\n"
                           "  cells: [" + std::to_string(n) + ", " + std::to_string(n) + ", " + std::to_string(n) +
                           "]\n  boundaries:\n    y_max: {type: wall, velocity: [1, 0, 0]}\n";
  gf::Params p = gf::Params::loadString(yaml, "bench.yaml");
  const gf::Domain domain = gf::Domain::read(p);
  gf::fluid::Solver solver(p, domain, gf::Vec3{});
  const double dt = 0.5 / n;
  for (int s = 0; s < 10; ++s) solver.step(dt);  // develop the flow first
  for (auto _ : state) solver.step(dt);
  state.counters["ns_per_cell_step"] = benchmark::Counter(
      1e-9 * static_cast<double>(solver.grid().interiorCellCount()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pressure_iterations"] = solver.lastStep().pressureIterations;
  state.counters["momentum_iterations"] = solver.lastStep().momentumIterations;
}
BENCHMARK(BM_FluidCavityStep)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

// Void fraction of the benchmark bed: 0.45 below z = 0.15 m except in a sphere of radius 25 mm
// (the bubble) centred at height zb; 1 above. Drag coefficient from Ergun (Gidaspow dense branch,
// d = 2.5 mm, mu = 1.8e-5, rho = 1.2, |u - v| = 1.875 m/s): K = 150 es^2 mu/(eps d^2) + 1.75 es rho |u|/d.
void setBedFields(gf::fluid::Solver& solver, double zb) {
  gf::CouplingFields& cf = solver.couplingFields();
  const gf::CartesianGrid& g = solver.grid();
  cf.voidFractionOld = cf.voidFraction;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) {
        const gf::Vec3 x = g.cellCentre(i, j, k);
        const double r2 = (x.y - 0.075) * (x.y - 0.075) + (x.z - zb) * (x.z - zb);
        const double eps = (x.z < 0.15 && r2 > 0.025 * 0.025) ? 0.45 : 1.0;
        const double es = 1.0 - eps, d = 2.5e-3;
        cf.voidFraction(i, j, k) = eps;
        cf.dragCoefficient(i, j, k) = eps < 1.0 ? 150.0 * es * es * 1.8e-5 / (eps * d * d) + 1.75 * es * 1.2 * 1.875 / d : 0.0;
      }
}

void BM_FluidBedStep(benchmark::State& state) {
  const std::string yaml =
      "domain: {min: [0, 0, 0], max: [0.015, 0.15, 0.45]}\nfluid:\n  density: 1.2\n  viscosity: 1.8e-5\n"
      "  cells: [2, 30, 90]\n  boundaries:\n    x_min: {type: slip}\n    x_max: {type: slip}\n"
      "    z_min: {type: inlet, velocity: [0, 0, 1.875]}\n    z_max: {type: pressure_outlet}\n"
      "  pressure: {tolerance: 1e-" + std::to_string(state.range(0)) + "}\n";
  gf::Params p = gf::Params::loadString(yaml, "bench.yaml");
  const gf::Domain domain = gf::Domain::read(p);
  gf::fluid::Solver solver(p, domain, gf::Vec3{0.0, 0.0, -9.81});
  const double dt = 2e-5;
  double zb = 0.06;  // bubble rises at 0.5 m/s (eps changes every step: d eps/dt in continuity)
  setBedFields(solver, zb);
  setBedFields(solver, zb);
  for (int s = 0; s < 50; ++s) {
    zb += 0.5 * dt;
    setBedFields(solver, zb);
    solver.step(dt);
  }
  double pressureIterations = 0.0, momentumIterations = 0.0, steps = 0.0;
  solver.timers().reset();
  for (auto _ : state) {
    state.PauseTiming();
    zb = zb > 0.12 ? 0.06 : zb + 0.5 * dt;
    setBedFields(solver, zb);
    state.ResumeTiming();
    solver.step(dt);
    pressureIterations += solver.lastStep().pressureIterations;
    momentumIterations += solver.lastStep().momentumIterations;
    steps += 1.0;
  }
  state.counters["ns_per_cell_step"] = benchmark::Counter(
      1e-9 * static_cast<double>(solver.grid().interiorCellCount()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pressure_iterations"] = pressureIterations / steps;
  state.counters["momentum_iterations"] = momentumIterations / steps;
  state.counters["max_divergence"] = solver.maxDivergence();
  const double cellSteps = steps * static_cast<double>(solver.grid().interiorCellCount());
  state.counters["pressure_ns_per_cell_step"] = 1e9 * solver.timers().seconds(gf::Phase::PressureSolve) / cellSteps;
}
BENCHMARK(BM_FluidBedStep)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

}  // namespace
