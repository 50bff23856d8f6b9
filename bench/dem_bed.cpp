// DEM throughput: dense bed (the issue-4 benchmark), free flight, and scaling with particle count.
// Counters: ns_per_particle_step (wall time / (particles x steps)), bytes_per_particle (all DEM
// arrays incl. neighbour list and contact history), rebuilds during the timed steps.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "dem/system.hpp"

namespace {

using gf::dem::System;

/// Bed of nx x ny x nz spheres (d = 2 mm, rho = 2500) on a simple-cubic lattice with small random
/// offsets, Hertz-Mindlin with history, E = 1e7, nu = 0.45, e = 0.3, mu = 0.5, in a box of
/// nx d x ny d x height; `spacing` = d gives a dense bed in contact (6 contacts each), larger
/// spacing gives free flight.
struct Bed {
  gf::Params params;
  gf::Domain domain;
  std::unique_ptr<System> system;
  Bed(int nx, int ny, int nz, double spacingFactor, bool walls) : params(gf::Params::loadString(yaml(nx, ny, nz, spacingFactor, walls), "bench.yaml")) {
    domain = gf::Domain::read(params);
    system = std::make_unique<System>(params, domain, gf::Vec3{0, 0, -9.81});
  }
  Bed(gf::Params p, const gf::Domain& d) : params(std::move(p)), domain(d) {
    system = std::make_unique<System>(params, domain, gf::Vec3{0, 0, -9.81});
  }
  static std::string yaml(int nx, int ny, int nz, double spacingFactor, bool walls) {
    const double d = 0.002, s = spacingFactor * d;
    const double lx = nx * s, ly = ny * s, lz = std::max(0.2, (nz + 2) * s);
    std::string out = fmt::format(R"(
materials:
  - {{name: glass, density: 2500, youngs_modulus: 1e7, poisson_ratio: 0.45}}
contact: {{law: hertz_mindlin, restitution: 0.3, friction: 0.5}}
domain: {{min: [0, 0, 0], max: [{}, {}, {}]}}
insertion:
  - {{type: lattice, origin: [{}, {}, {}], spacing: {}, nx: {}, ny: {}, nz: {}, size: {{diameter: {}}}}}
neighbour_search: {{skin: 0.0002}}
)",
                                  lx, ly, lz, 0.5 * s, 0.5 * s, 0.5 * d, s, nx, ny, nz, d);
    if (walls) out += fmt::format("walls:\n  - {{type: box, min: [0, 0, 0], max: [{}, {}, {}]}}\n", lx, ly, lz);
    return out;
  }
};

void runSteps(benchmark::State& state, Bed& bed, int warmup) {
  System& s = *bed.system;
  const double dt = 2e-6;
  for (int k = 0; k < warmup; ++k) s.step(dt);
  const long long rebuilds0 = s.rebuilds();
  long long steps = 0;
  for (auto _ : state) {
    s.step(dt);
    ++steps;
  }
  const double n = static_cast<double>(s.particles().size());
  state.counters["particles"] = n;
  state.counters["ns_per_particle_step"] = benchmark::Counter(
      n * static_cast<double>(steps) * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["bytes_per_particle"] = static_cast<double>(s.memoryBytes()) / n;
  state.counters["contacts_per_particle"] = s.contactStatistics().coordinationNumber;
  state.counters["rebuilds"] = static_cast<double>(s.rebuilds() - rebuilds0);
}

// ~15,000 spheres (30 x 30 x 17) in a 0.06 x 0.06 x 0.2 m box.
void BM_DemDenseBed(benchmark::State& state) {
  Bed bed(30, 30, 17, 1.0, true);
  runSteps(state, bed, 200);
}
BENCHMARK(BM_DemDenseBed)->Unit(benchmark::kMillisecond)->MinTime(3.0)->UseRealTime();

// Upper bound on contact density: ~15,900 spheres on a face-centred cubic lattice (nearest
// distance d: 12 touching neighbours each, twice a random dense bed), inserted from a CSV file.
void BM_DemDenseBedFcc(benchmark::State& state) {
  const double d = 0.002, a = d * std::sqrt(2.0);
  const int cells = 21, layers = 9;
  const std::string csv = (std::filesystem::temp_directory_path() / "grainflow_bench_fcc.csv").string();
  {
    std::ofstream out(csv);
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int k = 0; k < layers; ++k)
      for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i)
          for (const auto& b : basis)
            out << fmt::format("{},{},{},{}\n", (i + b[0]) * a + 0.5 * d, (j + b[1]) * a + 0.5 * d,
                               (k + b[2]) * a + 0.5 * d, 0.5 * d);
  }
  const double l = cells * a + 0.5 * d;
  const std::string yaml = fmt::format(R"(
materials:
  - {{name: glass, density: 2500, youngs_modulus: 1e7, poisson_ratio: 0.45}}
contact: {{law: hertz_mindlin, restitution: 0.3, friction: 0.5}}
domain: {{min: [0, 0, 0], max: [{}, {}, 0.2]}}
insertion:
  - {{type: csv_file, file: {}}}
walls:
  - {{type: box, min: [0, 0, 0], max: [{}, {}, 0.2]}}
neighbour_search: {{skin: 0.0002}}
)",
                                       l, l, csv, l, l);
  gf::Params params = gf::Params::loadString(yaml, "bench.yaml");
  const gf::Domain domain = gf::Domain::read(params);
  Bed bed(params, domain);
  runSteps(state, bed, 200);
}
BENCHMARK(BM_DemDenseBedFcc)->Unit(benchmark::kMillisecond)->MinTime(3.0)->UseRealTime();

// Same count, spacing 3 d: no contacts, gravity only.
void BM_DemFreeFlight(benchmark::State& state) {
  Bed bed(30, 30, 17, 3.0, false);
  runSteps(state, bed, 20);
}
BENCHMARK(BM_DemFreeFlight)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

// Dense beds of 1e4 .. 1e6 particles (square layers, 20 layers high).
void BM_DemDenseBedScaling(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int side = static_cast<int>(std::lround(std::sqrt(n / 20.0)));
  Bed bed(side, side, 20, 1.0, true);
  runSteps(state, bed, 20);
}
BENCHMARK(BM_DemDenseBedScaling)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)->UseRealTime();

}  // namespace
