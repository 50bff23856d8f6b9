// Thread team cost on this host: ns per gf::TeamBarrier round (the pressure solve synchronises
// ~13 times per CG iteration, the momentum team 4 + sweeps times per step) and the CPUs the team
// actually runs on. Counters:
//   ns_per_barrier  wall time of one barrier round of the whole team
//   members         threads in the team
//   team_cpus       distinct CPUs in the union of the members' CPU masks (1 with 2 members: the
//                   team shares one CPU, e.g. a bound initial thread's mask inherited; its
//                   timings then say nothing about two cores)
#include <benchmark/benchmark.h>
#include <omp.h>
#include <sched.h>

#include "core/parallel.hpp"

namespace {

void BM_TeamBarrier(benchmark::State& state) {
  const int team = gf::threadCount();
  constexpr int kRounds = 1000;
  gf::TeamBarrier barrier(team);
  cpu_set_t all;
  CPU_ZERO(&all);
  int members = 1;
  for (auto _ : state) {
#pragma omp parallel num_threads(team)
    {
      for (int r = 0; r < kRounds; ++r) barrier.wait();
#pragma omp single
      members = omp_get_num_threads();
#pragma omp critical(team_barrier_mask)
      {
        cpu_set_t mine;
        CPU_ZERO(&mine);
        if (sched_getaffinity(0, sizeof(mine), &mine) == 0) CPU_OR(&all, &all, &mine);
      }
    }
  }
  state.counters["ns_per_barrier"] = benchmark::Counter(static_cast<double>(state.iterations()) * kRounds * 1e-9,
                                                        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["members"] = members;
  state.counters["team_cpus"] = CPU_COUNT(&all);
}
BENCHMARK(BM_TeamBarrier)->Unit(benchmark::kMicrosecond)->MinTime(0.2)->UseRealTime();

}  // namespace
