// Coupling cost per particle and coupling step: 25,000 particles (d = 2 mm) in the lower half of
// a pseudo-2D bed on a 2 x 30 x 90 grid (5 mm cells). Reports ns per particle per coupling step
// for the void fraction (stencils + eps), the particle forces, and the fluid sources.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>
#include <vector>
#include <string>

#include "core/coupling_fields.hpp"
#include "core/params.hpp"
#include "coupling/coupler.hpp"
#include "dem/particles.hpp"

namespace {

using namespace gf;

constexpr int kParticles = 25000;
const char* kSchemes[] = {"pcm", "divided", "kernel", "big_particle"};

/// A uniform upflow u_z with a uniform pressure gradient on a grid, and its coupling fields.
struct UniformFlow {
  Field u[3], gradP[3];
  CouplingFields fields;
  double density = 1000.0, viscosity = 1e-3, timeStep = 1e-4;
  void setUp(const CartesianGrid& grid, double uz, double dpdz) {
    for (int a = 0; a < 3; ++a) {
      u[a] = Field(grid);
      gradP[a] = Field(grid);
    }
    for (auto& val : u[2].data()) val = uz;
    for (auto& val : gradP[2].data()) val = dpdz;
    fields = CouplingFields(grid);
  }
  coupling::FluidView view() const {
    coupling::FluidView f;
    for (int a = 0; a < 3; ++a) {
      f.velocity[a] = &u[a];
      f.pressureGradient[a] = &gradP[a];
    }
    f.density = density;
    f.viscosity = viscosity;
    f.timeStep = timeStep;
    return f;
  }
};

struct Bed : UniformFlow {
  CartesianGrid grid;
  dem::ParticleSet particles;
  Bed() {
    grid.cells = {2, 30, 90};
    grid.spacing = {0.005, 0.005, 0.005};
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> x(0.001, 0.009), y(0.001, 0.149), z(0.001, 0.224), v(-0.1, 0.1);
    for (int i = 0; i < kParticles; ++i) particles.add(i, 0, 0.001, 2500.0, {x(rng), y(rng), z(rng)}, {v(rng), v(rng), v(rng)});
    setUp(grid, 0.5, -9810.0);
  }
};

std::unique_ptr<coupling::Coupler> makeCoupler(const Bed& bed, const std::string& scheme, const std::string& extra) {
  Params p = Params::loadString("coupling:\n  void_fraction: " + scheme + "\n" + extra, "bench.yaml");
  return std::make_unique<coupling::Coupler>(p, bed.grid, std::array<bool, 3>{true, false, false}, Vec3{0, 0, -9.81});
}

void setCounter(benchmark::State& state) {
  // seconds per particle and coupling step (printed with SI prefix, e.g. "95n" = 95 ns)
  state.counters["ns_per_particle_step"] = benchmark::Counter(
      static_cast<double>(kParticles), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_CouplingVoidFraction(benchmark::State& state) {
  Bed bed;
  auto c = makeCoupler(bed, kSchemes[state.range(0)], "");
  for (auto _ : state) c->computeVoidFraction(bed.particles, bed.fields);
  state.SetLabel(kSchemes[state.range(0)]);
  setCounter(state);
}

void BM_CouplingFullStep(benchmark::State& state) {
  // void fraction + drag (Di Felice) + pressure + viscous forces + semi-implicit sources
  Bed bed;
  auto c = makeCoupler(bed, kSchemes[state.range(0)], "  interpolation: trilinear\n");
  const auto view = bed.view();
  for (auto _ : state) {
    c->computeVoidFraction(bed.particles, bed.fields);
    c->computeParticleForces(view, bed.fields, bed.particles);
    c->fillFluidSources(bed.fields);
  }
  state.SetLabel(kSchemes[state.range(0)]);
  setCounter(state);
}

void BM_CouplingForcesAllOn(benchmark::State& state) {
  // forces and sources only, every force on (lifts, virtual mass, torque), divided scheme
  Bed bed;
  auto c = makeCoupler(bed, "divided",
                       "  forces:\n    virtual_mass: true\n    saffman_mei_lift: true\n    magnus_lift: true\n"
                       "    fluid_torque: true\n");
  const auto view = bed.view();
  c->computeVoidFraction(bed.particles, bed.fields);
  for (auto _ : state) {
    c->computeParticleForces(view, bed.fields, bed.particles);
    c->fillFluidSources(bed.fields);
  }
  setCounter(state);
}

/// The pseudo-2D bubbling bed of cases/cfddem_bubbling_fluidised_bed.yaml: 24,750 spheres of
/// d = 2.5 mm, 15 x 150 x 450 mm on a 2 x 30 x 90 grid (7.5 x 5 x 5 mm cells, walls), air,
/// Gidaspow drag, divided void fraction, trilinear interpolation, implicit exchange. 80 % of the
/// spheres in a bed of mean eps ~ 0.5 (Ergun branch), 20 % above it (Wen-Yu branch); particles
/// sorted by cell, as the DEM's Morton reordering leaves them.
struct BubblingBed : UniformFlow {
  static constexpr int kCount = 24750;
  CartesianGrid grid;
  dem::ParticleSet particles;
  BubblingBed() {
    grid.cells = {2, 30, 90};
    grid.spacing = {0.0075, 0.005, 0.005};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> x(0.00125, 0.01375), y(0.00125, 0.14875), bed(0.00625, 0.17),
        top(0.17, 0.3), v(-0.2, 0.2);
    struct P { double key; Vec3 x, v; };
    std::vector<P> ps;
    for (int i = 0; i < kCount; ++i) {
      const Vec3 pos{x(rng), y(rng), i % 5 == 4 ? top(rng) : bed(rng)};
      const auto c = grid.cellOf(pos);
      ps.push_back({(c[2] * 30.0 + c[1]) * 2.0 + c[0] + 0.5 * pos.z, pos, {v(rng), v(rng), v(rng)}});
    }
    std::sort(ps.begin(), ps.end(), [](const P& a, const P& b) { return a.key < b.key; });
    for (int i = 0; i < kCount; ++i) particles.add(i, 0, 0.00125, 2526.0, ps[i].x, ps[i].v);
    density = 1.2;  // air
    viscosity = 1.8e-5;
    timeStep = 2e-5;
    setUp(grid, 3.5, -12000.0);
  }
};

void BM_CouplingBubblingBed(benchmark::State& state) {
  // one coupling step of the bed as Simulation::advance does it (void fraction, forces, sources)
  BubblingBed bed;
  Params p = Params::loadString("coupling:\n  drag_law: gidaspow\n  void_fraction: divided\n", "bench.yaml");
  coupling::Coupler c(p, bed.grid, {false, false, false}, Vec3{0, 0, -9.81});
  const auto view = bed.view();
  c.computeVoidFraction(bed.particles, bed.fields);
  for (auto _ : state) {
    c.computeParticleForces(view, bed.fields, bed.particles);
    c.computeVoidFraction(bed.particles, bed.fields);
    c.fillFluidSources(bed.particles, bed.fields);
  }
  state.counters["ns_per_particle_step"] = benchmark::Counter(
      static_cast<double>(BubblingBed::kCount), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_CouplingBubblingBedPhase(benchmark::State& state) {
  // the parts of the bed's coupling step: 0 = forces (computeParticleForces), 1 = void fraction
  // alone (stencils and eps, no exchange pending), 2 = void fraction with the fused exchange
  // deposit + fluid sources (computeVoidFraction + fillFluidSources after the forces)
  BubblingBed bed;
  Params p = Params::loadString("coupling:\n  drag_law: gidaspow\n  void_fraction: divided\n", "bench.yaml");
  coupling::Coupler c(p, bed.grid, {false, false, false}, Vec3{0, 0, -9.81});
  const auto view = bed.view();
  c.computeVoidFraction(bed.particles, bed.fields);
  c.computeParticleForces(view, bed.fields, bed.particles);
  const int phase = static_cast<int>(state.range(0));
  for (auto _ : state) {
    if (phase == 0) {
      c.computeParticleForces(view, bed.fields, bed.particles);
    } else if (phase == 1) {
      c.computeVoidFraction(bed.particles, bed.fields);
    } else {
      state.PauseTiming();
      c.computeParticleForces(view, bed.fields, bed.particles);
      state.ResumeTiming();
      c.computeVoidFraction(bed.particles, bed.fields);
      c.fillFluidSources(bed.particles, bed.fields);
    }
  }
  const char* names[] = {"forces", "void_fraction", "void_fraction+sources"};
  state.SetLabel(names[phase]);
  state.counters["ns_per_particle_step"] = benchmark::Counter(
      static_cast<double>(BubblingBed::kCount), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_CouplingBubblingBedPhase)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CouplingBubblingBed)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CouplingVoidFraction)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CouplingFullStep)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CouplingForcesAllOn)->Unit(benchmark::kMillisecond)->UseRealTime();
