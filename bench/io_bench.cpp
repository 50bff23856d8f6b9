// Output cost: VTK XML (base64 binary) particle file, per particle.
#include <benchmark/benchmark.h>

#include "dem/particles.hpp"
#include "io/vtk.hpp"

static void BM_ParticlesVtu(benchmark::State& state) {
  gf::dem::ParticleSet particles;
  const auto n = static_cast<std::size_t>(state.range(0));
  for (std::size_t i = 0; i < n; ++i)
    particles.add(static_cast<std::int64_t>(i), 0, 0.001, 2500.0, {1e-3 * i, 2e-3 * i, 3e-3 * i});
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::string xml = gf::io::particlesVtu(particles);
    bytes = xml.size();
    benchmark::DoNotOptimize(xml);
  }
  state.counters["ns_per_particle"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["bytes_per_particle"] = static_cast<double>(bytes) / static_cast<double>(n);
}
BENCHMARK(BM_ParticlesVtu)->Arg(100000)->Unit(benchmark::kMillisecond);
