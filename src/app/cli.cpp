#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <omp.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <vector>

#include "app/docs.hpp"
#include "app/plot.hpp"
#include "app/validate.hpp"
#include "app/simulation.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "parallel/environment.hpp"
#include "grainflow_version.hpp"

namespace gf::app {

namespace {

void printError(const std::string& message) { std::fprintf(stderr, "grainflow: %s\n", message.c_str()); }

/// Under MPI: whether this process is a rank other than 0.
bool otherRank() { return parallel::Environment::initialised() && parallel::Environment::instance().rank() != 0; }

/// An error that every rank meets the same way (a case-file error: every rank reads the same
/// file; a divergence: the health check is collective): printed once, by rank 0.
int collectiveError(const std::string& message, int code) {
  if (!otherRank()) printError(message);
  return code;
}

/// An error that may have struck this rank alone (a file it could not write or read): printed with
/// its rank, and under MPI every rank is stopped with the same exit code (the others may be waiting
/// for this one).
int rankError(const std::string& message, int code) {
  if (!parallel::Environment::initialised() || parallel::Environment::instance().size() == 1) {
    printError(message);
    return code;
  }
  printError(fmt::format("rank {}: {}", parallel::Environment::instance().rank(), message));
  std::fflush(stderr);
  parallel::Environment::instance().abortAll(code);
  return code;
}

int commandCheck(const std::string& caseFile, int threads) {
  setThreadCount(threads);
  RunOptions options;
  auto simulation = Simulation::fromFile(caseFile, options);
  std::fputs(fmt::format("# {}: valid case '{}'\n", caseFile, simulation->settings().name).c_str(), stdout);
  std::fputs(simulation->resolvedCase().c_str(), stdout);
  const auto& particles = simulation->dem().particles();
  std::fputs(fmt::format("# particles: {}\n", particles.size()).c_str(), stdout);
  const double rayleigh = simulation->dem().rayleighTime();  // (one pass over the particles)
  if (std::isfinite(rayleigh))                                 // (particles present or insertable)
    std::fputs(fmt::format("# DEM step {:g} s = {:.1f} % of the Rayleigh time {:.4g} s\n", simulation->settings().demStep,
                           100.0 * simulation->settings().demStep / rayleigh, rayleigh)
                   .c_str(),
               stdout);
  return kExitOk;
}

int commandRun(const std::string& caseFile, RunOptions options) {
  setThreadCount(options.threads);
  // Under MPI the warnings of reading the case come from rank 0 only.
  if (parallel::Environment::launched() && parallel::Environment::launchedRank() != 0)
    spdlog::set_level(spdlog::level::err);
  auto simulation = Simulation::fromFile(caseFile, options);
  // Under MPI only rank 0 reports (progress, timing, warnings); every rank stops on an error, and
  // rank 0 prints it.
  if (!simulation->rootRank()) {
    options.quiet = true;
    spdlog::set_level(spdlog::level::err);
  }
  simulation->prepare();
  const auto& s = simulation->settings();
  const long long particleCount = simulation->dem().globalParticleCount();
  const int ranks = simulation->decomposition().ranks();
  if (!options.quiet)
    std::printf("grainflow %s: case '%s', %lld particles, %s%d thread(s)%s, output in %s\n", GRAINFLOW_VERSION,
                s.name.c_str(), particleCount, ranks > 1 ? fmt::format("{} ranks ({}) x ", ranks, simulation->decomposition().describe()).c_str() : "",
                threadCount(), ranks > 1 ? " each" : "", s.outputDirectory.c_str());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  const double startTime = simulation->time();
  const long long startSteps = simulation->dem().steps(), startRebuilds = simulation->dem().rebuilds();
  RunStatus status;
  try {
    status = simulation->run();
  } catch (const DivergenceError& e) {
    if (!simulation->rootRank()) return kExitDiverged;  // (the same error on every rank; rank 0 prints it)
    printError(e.what());
    const std::string last = simulation->lastGoodCheckpoint();
    printError(last.empty() ? "no checkpoint had been written before the divergence"
                            : fmt::format("last good checkpoint kept: {}", last));
    return kExitDiverged;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (status == RunStatus::Interrupted) {
    if (!simulation->rootRank()) return kExitInterrupted;
    printError(fmt::format("interrupted at t = {:.6g} s (step {}); checkpoint written to {} (continue with --restart)",
                           simulation->time(), simulation->step(), simulation->checkpointPath()));
    return kExitInterrupted;
  }
  const long long finalCount = simulation->dem().globalParticleCount();  // (collective: every rank)
  if (!options.quiet) {
    std::printf("\n%s", simulation->timingTable(wall, simulation->time() - startTime, finalCount).c_str());
    const long long steps = simulation->dem().steps() - startSteps;
    const long long rebuilds = simulation->dem().rebuilds() - startRebuilds;
    if (steps > 0)  // (as LAMMPS' "Neighbor list builds"): the displacement criterion's rate
      std::printf("neighbour lists    %lld builds in %lld DEM steps (every %.1f steps)\n", rebuilds, steps,
                  rebuilds > 0 ? static_cast<double>(steps) / static_cast<double>(rebuilds) : 0.0);
    if (ranks > 1) {  // (the phases above are rank 0's)
      const auto& p = simulation->dem().particles();
      const std::size_t owned = p.ownedCount();
      std::printf("MPI                %d ranks (%s); the phases are rank 0's", ranks,
                  simulation->dem().decomposition().describe().c_str());
      if (finalCount > 0)
        std::printf(", which owns %zu particles and holds %zu ghosts (%.0f %%)", owned, p.size() - owned,
                    owned ? 100.0 * static_cast<double>(p.size() - owned) / static_cast<double>(owned) : 0.0);
      std::printf("\n");
    }
    std::printf("\noutput written to %s/\n", s.outputDirectory.c_str());
    if (s.outputInterval > 0.0 && s.writeParticles)
      std::printf("view it in ParaView: paraview %s/particles.pvd  (Glyph filter, scale by 'radius' x2, sphere glyphs)\n",
                  s.outputDirectory.c_str());
    std::printf("monitors (CSV) are in the same directory; restart file: %s\n", simulation->checkpointPath().c_str());
  }
  return kExitOk;
}

/// Widens this thread's CPU mask to all CPUs of the OpenMP places (no-op without places). With
/// OMP_PROC_BIND set, libgomp binds the initial thread to the first place when it loads, and an
/// exec'd program inherits that mask: its libgomp then sees only that place's CPUs and binds the
/// whole team there (grainflow bench with OMP_PLACES={0},{1}: both threads on CPU 0, 171,000
/// context switches in a 12 s run, slower than one thread).
void widenAffinityToOmpPlaces() {
  const int places = omp_get_num_places();
  if (places <= 0) return;
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  for (int place = 0; place < places; ++place) {
    std::vector<int> ids(static_cast<std::size_t>(omp_get_place_num_procs(place)));
    omp_get_place_proc_ids(place, ids.data());
    for (int id : ids)
      if (id >= 0 && id < CPU_SETSIZE) CPU_SET(id, &cpus);
  }
  if (CPU_COUNT(&cpus) > 0 && sched_setaffinity(0, sizeof(cpus), &cpus) != 0)
    spdlog::warn("bench: cannot widen the CPU mask to the OpenMP places; the benchmarks may run on fewer CPUs");
}

int commandBench(const std::string& name, int threads) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path bench = self.parent_path() / "bench" / "grainflow_bench";
  if (!fs::exists(bench)) {
    printError(fmt::format("benchmark executable not found at {} (build with -DGRAINFLOW_BUILD_BENCH=ON)", bench.string()));
    return kExitIo;
  }
  if (threads > 0) setenv("OMP_NUM_THREADS", std::to_string(threads).c_str(), 1);
  std::string filter = "--benchmark_filter=" + (name.empty() ? std::string(".") : name);
  std::string counters = "--benchmark_counters_tabular=true";
  widenAffinityToOmpPlaces();  // (the benchmark process binds its own team to the places)
  execl(bench.c_str(), bench.c_str(), filter.c_str(), counters.c_str(), static_cast<char*>(nullptr));
  printError(fmt::format("cannot start {}", bench.string()));
  return kExitIo;
}

}  // namespace

int runCommandLine(int argc, char** argv) {
  CLI::App app{"grainflow: CFD-DEM solver (DEM particles coupled to volume-averaged incompressible flow)"};
  bool showVersion = false;
  app.add_flag("--version", showVersion, "print the version and exit");
  app.require_subcommand(0, 1);

  std::string caseFile;
  RunOptions runOptions;
  std::string outputDirectory, restartFile;
  double endTime = -1.0;
  auto* run = app.add_subcommand("run", "run a case");
  run->add_option("case", caseFile, "case file (YAML)")->required();
  run->add_option("--threads", runOptions.threads, "OpenMP threads (default: all cores)")->check(CLI::NonNegativeNumber);
  run->add_option("--output", outputDirectory, "output directory (overrides output.directory)");
  run->add_option("--end-time", endTime, "simulated end time in s (overrides time.end)")->check(CLI::NonNegativeNumber);
  run->add_option("--restart", restartFile, "continue from this checkpoint file");
  run->add_flag("--overwrite", runOptions.overwrite, "replace the output of an earlier run in the output directory");
  run->add_flag("--quiet", runOptions.quiet, "no progress lines or summary");

  int checkThreads = 0;
  auto* check = app.add_subcommand("check", "validate a case file and print it with all defaults and units");
  check->add_option("case", caseFile, "case file (YAML)")->required();
  check->add_option("--threads", checkThreads, "OpenMP threads")->check(CLI::NonNegativeNumber);

  std::string benchName;
  int benchThreads = 0;
  auto* bench = app.add_subcommand("bench", "run the benchmarks (all, or those matching NAME)");
  bench->add_option("name", benchName, "benchmark name filter (regular expression)");
  bench->add_option("--threads", benchThreads, "OpenMP threads")->check(CLI::NonNegativeNumber);

  auto* docs = app.add_subcommand("docs", "print the case-file reference (Markdown), generated from the schema");

  // validate / plot (see src/app/validate.hpp and docs/validation-format.md)
  ValidateOptions validateOptions;
  auto* validate = app.add_subcommand("validate", "run the validation items (validation/*/validation.yaml), compare with the references");
  validate->add_option("names", validateOptions.names, "items to run (default: all)");
  validate->add_flag("--quick", validateOptions.quick, "reduced durations/resolutions (as in ctest); does not rewrite docs");
  validate->add_option("--dir", validateOptions.validationDirectory, "validation directory (default: ./validation or the source tree's)");
  validate->add_option("--output", validateOptions.outputDirectory, "where runs, results.csv and plots go (default: output/validation)");
  validate->add_option("--docs", validateOptions.docsDirectory, "where full mode writes validation.md and img/ (default: <dir>/../docs)");
  validate->add_flag("--no-docs", [&](std::int64_t) { validateOptions.writeDocs = false; }, "do not rewrite docs/validation.md");
  validate->add_flag("--no-plots", [&](std::int64_t) { validateOptions.plots = false; }, "numbers only");
  validate->add_option("--threads", validateOptions.threads, "OpenMP threads")->check(CLI::NonNegativeNumber);
  std::string plotDirectory;
  auto* plot = app.add_subcommand("plot", "one PNG per monitor CSV of a run, written next to the CSVs");
  plot->add_option("output", plotDirectory, "output directory of a run")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  if (showVersion) {
    std::printf("grainflow %s\n", GRAINFLOW_VERSION);
    return kExitOk;
  }
  if (app.get_subcommands().empty()) {
    std::fputs(app.help().c_str(), stderr);
    return kExitUsage;
  }
  spdlog::set_pattern("grainflow: %l: %v");
  try {
    if (*run) {
      if (!outputDirectory.empty()) runOptions.outputDirectory = outputDirectory;
      if (!restartFile.empty()) runOptions.restartFile = restartFile;
      if (endTime >= 0.0) runOptions.endTime = endTime;
      return commandRun(caseFile, runOptions);
    }
    if (*check) return commandCheck(caseFile, checkThreads);
    if (*bench) return commandBench(benchName, benchThreads);
    if (*validate) return runValidate(validateOptions);
    if (*plot) return plotRunOutput(plotDirectory);
    if (*docs) {
      std::fputs(caseFileReference().c_str(), stdout);
      return kExitOk;
    }
  } catch (const CaseError& e) {
    return collectiveError(e.what(), kExitInvalidCase);
  } catch (const CheckpointError& e) {
    return rankError(e.what(), kExitCheckpoint);
  } catch (const DivergenceError& e) {
    return collectiveError(e.what(), kExitDiverged);
  } catch (const Error& e) {
    return rankError(e.what(), kExitIo);
  } catch (const std::filesystem::filesystem_error& e) {
    return rankError(e.what(), kExitIo);
  }
  return kExitUsage;
}

}  // namespace gf::app
