// The fluid step with a VOF mixture against the single-fluid step on the same grid (docs/vof.md):
//  - BM_VofStep/n: one step of a 3D dam break (cases/vof_dam_break.yaml made 3D: a water column
//    a x 2a x the depth under air, 1000:1, gravity, open top) on n x n/2 x n/4 cells with the
//    case's step (0.2 ms at n = 80), timed from 20 steps after the release; counters: ns per cell
//    per step, phase-transport substeps, pressure iterations.
//  - BM_VofSinglePhaseStep/n: one step of the single fluid (water) on the same grid and step, a
//    lid at 1 m/s (the dam break's speeds), closed box; counters: ns per cell per step, pressure
//    iterations.
// The ratio of the two ns_per_cell_step figures is the VOF step's cost over the single fluid's
// (grainflow bench 'Vof' runs both, alternating nothing: run it on an otherwise idle machine).
#include <benchmark/benchmark.h>

#include <string>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "fluid/solver.hpp"

namespace {

std::string boxYaml(int n, const std::string& body) {
  const double L = 0.28575, H = 0.142875, D = 0.0714375;  // the dam break's box, 1/4 of its length deep
  return "domain: {min: [0, 0, 0], max: [" + std::to_string(L) + ", " + std::to_string(H) + ", " + std::to_string(D) +
         "]}\nfluid:\n  cells: [" + std::to_string(n) + ", " + std::to_string(n / 2) + ", " + std::to_string(n / 4) +
         "]\n  pressure: {tolerance: 1.0e-8}\n" + body;
}

void countCellSteps(benchmark::State& state, const gf::fluid::Solver& solver) {
  state.counters["ns_per_cell_step"] =
      benchmark::Counter(1e-9 * static_cast<double>(solver.grid().interiorCellCount()),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["pressure_iterations"] = solver.lastStep().pressureIterations;
  state.counters["cells"] = static_cast<double>(solver.grid().interiorCellCount());
}

void BM_VofStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string yaml = boxYaml(n,
                                   "  vof:\n    phases:\n"
                                   "      - {name: air, density: 1.0, viscosity: 1.0e-5}\n"
                                   "      - {name: water, density: 1000.0, viscosity: 1.0e-3}\n"
                                   "    regions:\n      - {phase: water, min: [0, 0, 0], max: [0.05715, 0.1143, 1]}\n"
                                   "  boundaries:\n    y_max: {type: pressure_outlet, pressure: 0.0}\n");
  gf::Params p = gf::Params::loadString(yaml, "bench.yaml");
  const gf::Domain domain = gf::Domain::read(p);
  gf::fluid::Solver solver(p, domain, gf::Vec3{0.0, -9.81, 0.0});
  const double dt = 2e-4 * 80.0 / n;
  for (int s = 0; s < 20; ++s) solver.step(dt);  // the column released and moving
  for (auto _ : state) solver.step(dt);
  countCellSteps(state, solver);
  state.counters["transport_substeps"] = solver.vofSubsteps();
}
BENCHMARK(BM_VofStep)->Arg(80)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

void BM_VofSinglePhaseStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const std::string yaml =
      boxYaml(n, "  density: 1000.0\n  viscosity: 1.0e-3\n  boundaries:\n    y_max: {type: wall, velocity: [1.0, 0, 0]}\n");
  gf::Params p = gf::Params::loadString(yaml, "bench.yaml");
  const gf::Domain domain = gf::Domain::read(p);
  gf::fluid::Solver solver(p, domain, gf::Vec3{});
  const double dt = 2e-4 * 80.0 / n;
  for (int s = 0; s < 20; ++s) solver.step(dt);
  for (auto _ : state) solver.step(dt);
  countCellSteps(state, solver);
}
BENCHMARK(BM_VofSinglePhaseStep)->Arg(80)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

}  // namespace
