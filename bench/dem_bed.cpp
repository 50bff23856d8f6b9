// DEM throughput: random settled bed (the reference benchmark), lattice beds, free flight, and
// scaling with particle count.
// Counters: ns_per_particle_step (wall time / (particles x steps)), bytes_per_particle (all DEM
// arrays incl. neighbour list and contact history), rebuilds during the timed steps.
#include <benchmark/benchmark.h>
#include <omp.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "dem/neighbour_list.hpp"
#include "dem/system.hpp"
#include "dem/wall_contact_list.hpp"
#include "io/atomic_file.hpp"

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

// ---------------------------------------------------------------------------------------------
// Random settled bed (the DEM reference benchmark, also timed against LIGGGHTS): spheres d = 2 mm,
// rho = 2500, Hertz-Mindlin with history, E = 1e7, nu = 0.45, e = 0.3, mu = 0.5, dt = 2e-6.
// Built at set-up, nothing cached on disk:
//  1. random sequential addition at solid fraction 0.22 in a tall region (geometric, cheap);
//  2. settling with the real Hertz law but frictionless (a denser, better-connected bed, as a
//     poured bed of rough spheres after tapping), dt = 1e-5 (11 % of the Rayleigh time) and
//     4 g for 0.06 s (a body force, so the fall is quick), then 1 g for 0.015 s;
//  3. the settled positions go into a system with the spec parameters (mu = 0.5), whose contacts
//     then build up their tangential history during the warm-up steps.
struct SettledTile {
  std::vector<gf::Vec3> position;
  double radius = 0.001, lx = 0, ly = 0;
};

std::string settledBedYaml(double lx, double ly, double friction, bool periodic, const std::string& insertion) {
  std::string out = fmt::format(R"(
materials:
  - {{name: glass, density: 2500, youngs_modulus: 1e7, poisson_ratio: 0.45}}
contact: {{law: hertz_mindlin, restitution: 0.3, friction: {}}}
domain: {{min: [0, 0, 0], max: [{}, {}, 0.2], periodic: [{}, {}, 0]}}
neighbour_search: {{skin: 0.0002}}
{}
)",
                                friction, lx, ly, periodic ? 1 : 0, periodic ? 1 : 0, insertion);
  if (periodic) out += "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1]}\n";
  else out += fmt::format("walls:\n  - {{type: box, min: [0, 0, 0], max: [{}, {}, 0.2]}}\n", lx, ly);
  return out;
}

SettledTile settleBed(double lx, double ly, int count, bool periodic) {
  const double d = 0.002;
  const double solid = count * std::numbers::pi / 6.0 * d * d * d;
  const double height = solid / (0.22 * lx * ly);
  const std::string insertion = fmt::format(
      "insertion:\n  - {{type: random_packing, min: [0, 0, 0], max: [{}, {}, {}], count: {}, seed: 11, "
      "size: {{diameter: {}}}}}\n",
      lx, ly, height, count, d);
  gf::Params params = gf::Params::loadString(settledBedYaml(lx, ly, 0.0, periodic, insertion), "settle.yaml");
  const gf::Domain domain = gf::Domain::read(params);
  const double g = 9.81;
  System s(params, domain, gf::Vec3{0, 0, -g});
  auto& p = s.particles();
  p.enableExternalForces();  // extra weight compacts the bed faster
  for (std::size_t i = 0; i < p.size(); ++i) p.externalForce[i] = gf::Vec3{0, 0, -3.0 * g * p.mass[i]};
  const double dt = 1e-5;
  for (int k = 0; k < 6000; ++k) s.step(dt);
  for (std::size_t i = 0; i < p.size(); ++i) p.externalForce[i] = gf::Vec3{};
  for (int k = 0; k < 1500; ++k) s.step(dt);
  SettledTile tile;
  tile.position = p.position;
  tile.radius = 0.5 * d;
  tile.lx = lx;
  tile.ly = ly;
  return tile;
}

void writeTileCsv(const SettledTile& tile, const std::string& path) {
  std::string csv;
  for (const gf::Vec3& x : tile.position) csv += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", x.x, x.y, x.z, tile.radius);
  gf::io::writeFileAtomically(path, csv);
}

/// The spec system filled with the tile repeated tx x ty times (periodic tiles only).
std::unique_ptr<Bed> bedFromTile(const SettledTile& tile, int tx, int ty, bool periodic) {
  const double lx = tile.lx * tx, ly = tile.ly * ty;
  gf::Params params = gf::Params::loadString(settledBedYaml(lx, ly, 0.5, periodic, ""), "bench.yaml");
  const gf::Domain domain = gf::Domain::read(params);
  auto bed = std::make_unique<Bed>(std::move(params), domain);
  auto& p = bed->system->particles();
  p.reserve(tile.position.size() * tx * ty);
  std::int64_t id = 0;
  for (int b = 0; b < ty; ++b)
    for (int a = 0; a < tx; ++a)
      for (const gf::Vec3& x : tile.position)
        p.add(id++, 0, tile.radius, 2500.0, x + gf::Vec3{a * tile.lx, b * tile.ly, 0.0});
  bed->system->refresh();
  return bed;
}

const SettledTile& issueBedTile() {
  static const SettledTile tile = settleBed(0.06, 0.06, 15000, false);
  return tile;
}

// ~15,000 spheres settled in the 0.06 x 0.06 x 0.2 m box (walls on all sides).
void BM_DemSettledBed(benchmark::State& state) {
  const auto start = std::chrono::steady_clock::now();
  const SettledTile& tile = issueBedTile();
  state.counters["setup_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The settled positions for the same bed in another code (bench/liggghts_settled_bed.sh):
  // x, y, z, r in m, one sphere per line, written to a temporary file and renamed.
  if (const char* path = std::getenv("GRAINFLOW_SETTLED_BED_CSV")) writeTileCsv(tile, path);
  auto bed = bedFromTile(tile, 1, 1, false);
  runSteps(state, *bed, 500);
}
BENCHMARK(BM_DemSettledBed)->Unit(benchmark::kMillisecond)->MinTime(3.0)->UseRealTime();

// The force loop's split from the threads' measured speeds against the equal-share split, on the
// settled bed: two copies of the bed in one process, stepped in turns of 50 steps (the order
// alternating), so both see the same host (a shared machine's speed drifts over seconds, which
// separate runs would compare instead). Same bits either way (docs/dem.md: the force sums do not
// depend on the split); equal_over_measured > 1: the measured split is faster. Meaningful with 2
// or more threads.
void BM_DemSettledBedSplit(benchmark::State& state) {
  const SettledTile& tile = issueBedTile();
  auto measured = bedFromTile(tile, 1, 1, false);
  auto equal = bedFromTile(tile, 1, 1, false);
  const int threads = omp_get_max_threads();
  equal->system->setThreadSpeeds(std::vector<double>(static_cast<std::size_t>(threads), 1.0));
  const double dt = 2e-6;
  constexpr int kTurn = 50;
  for (int k = 0; k < 500; ++k) {
    measured->system->step(dt);
    equal->system->step(dt);
  }
  double secondsMeasured = 0.0, secondsEqual = 0.0;
  long long turns = 0;
  auto turn = [&](System& s) {
    const auto begin = std::chrono::steady_clock::now();
    for (int k = 0; k < kTurn; ++k) s.step(dt);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  };
  for (auto _ : state) {
    if (turns % 2 == 0) {
      secondsMeasured += turn(*measured->system);
      secondsEqual += turn(*equal->system);
    } else {
      secondsEqual += turn(*equal->system);
      secondsMeasured += turn(*measured->system);
    }
    ++turns;
  }
  const double particleSteps = static_cast<double>(measured->system->particles().size()) * kTurn * static_cast<double>(turns);
  state.counters["ns_measured_split"] = 1e9 * secondsMeasured / particleSteps;
  state.counters["ns_equal_split"] = 1e9 * secondsEqual / particleSteps;
  state.counters["equal_over_measured"] = secondsEqual / secondsMeasured;
  state.counters["threads"] = threads;
}
BENCHMARK(BM_DemSettledBedSplit)->Unit(benchmark::kMillisecond)->MinTime(10.0)->UseRealTime();

// Neighbour-list build of the settled bed above (linked cells, candidate test, history carried
// over from the previous build of the same particles, as at a rebuild without reordering; on a
// team also the touching pairs per row).
void BM_DemNeighbourBuild(benchmark::State& state) {
  static const SettledTile tile = settleBed(0.06, 0.06, 15000, false);
  auto bed = bedFromTile(tile, 1, 1, false);
  const gf::dem::ParticleSet& p = std::as_const(*bed->system).particles();
  const gf::dem::PeriodicBox box(bed->domain);
  std::vector<std::int64_t> previous(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) previous[i] = static_cast<std::int64_t>(i);
  gf::dem::NeighbourList list;
  list.build(p, box, bed->domain.min, bed->domain.max, 0.0002, {}, false);
  for (auto _ : state) list.build(p, box, bed->domain.min, bed->domain.max, 0.0002, previous, false);
  state.counters["ns_per_particle"] = benchmark::Counter(static_cast<double>(p.size()) * state.iterations() * 1e-9,
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["entries_per_particle"] = static_cast<double>(list.entries()) / static_cast<double>(p.size());
}
BENCHMARK(BM_DemNeighbourBuild)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

// Wall contact list of the settled bed above on a meshed floor (an STL wall of 28,800 triangles,
// 120 x 120 squares, slightly wavy, under the bottom layer): ns per particle per build.
void BM_DemWallListMesh(benchmark::State& state) {
  static const SettledTile tile = settleBed(0.06, 0.06, 15000, false);
  gf::dem::ParticleSet p;
  for (std::size_t i = 0; i < tile.position.size(); ++i)
    p.add(static_cast<std::int64_t>(i), 0, tile.radius, 2500.0, tile.position[i]);
  const int cells = 120;
  const double h = 0.06 / cells;
  auto floor = [&](int i, int j) {
    return gf::Vec3{i * h, j * h, 0.0002 * std::sin(100.0 * i * h) * std::cos(100.0 * j * h)};
  };
  std::vector<gf::dem::WallPrimitive> mesh;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      gf::dem::WallPrimitive t;
      t.kind = gf::dem::PrimitiveKind::Triangle;
      t.a = floor(i, j), t.b = floor(i + 1, j), t.c = floor(i + 1, j + 1);
      mesh.push_back(t);
      t.b = floor(i + 1, j + 1), t.c = floor(i, j + 1);
      mesh.push_back(t);
    }
  gf::dem::WallContactList list;
  for (auto _ : state) list.build(p, mesh, 0.0002, {}, false);
  state.counters["ns_per_particle"] = benchmark::Counter(static_cast<double>(p.size()) * state.iterations() * 1e-9,
                                                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["entries_per_particle"] = static_cast<double>(list.entries()) / static_cast<double>(p.size());
  state.counters["triangles"] = static_cast<double>(mesh.size());
}
BENCHMARK(BM_DemWallListMesh)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();

// The same random bed from 1e4 to 1e6 particles: a settled tile of 3,750 spheres
// (0.03 x 0.03 m, periodic in x and y, on a floor) repeated side by side.
void BM_DemSettledBedScaling(benchmark::State& state) {
  static const SettledTile tile = settleBed(0.03, 0.03, 3750, true);
  const double tiles = static_cast<double>(state.range(0)) / tile.position.size();
  const int tx = std::max(1, static_cast<int>(std::lround(std::sqrt(tiles))));
  const int ty = std::max(1, static_cast<int>(std::lround(tiles / tx)));
  auto bed = bedFromTile(tile, tx, ty, true);
  runSteps(state, *bed, 100);
}
BENCHMARK(BM_DemSettledBedScaling)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)->UseRealTime();

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
