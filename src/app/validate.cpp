#include "app/validate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/cli.hpp"
#include "app/plot.hpp"
#include "app/simulation.hpp"
#include "app/validation_plot_spec.hpp"
#include "app/validation_report.hpp"
#include "app/validation_results.hpp"
#include "app/validation_spec.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "fluid/solver.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_series.hpp"

namespace gf::app {

namespace fs = std::filesystem;
using namespace validation;

namespace {

struct PlannedRun {
  std::size_t item = 0;
  std::size_t run = 0;  // index into item.runsFor(quick)
  std::string caseFile;
  std::string outputDirectory;
  double work = 1.0;  // steps x (particles + 20) + 4 x fluid steps x cells, for the ETA
  long long steps = 0;
  std::size_t particles = 0;
};

std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e8) return "--:--";
  const long long s = std::llround(seconds);
  return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, (s % 3600) / 60, s % 60) : fmt::format("{:02d}:{:02d}", s / 60, s % 60);
}

std::string defaultValidationDirectory() {
  if (fs::exists("validation")) return "validation";
  return (fs::path(GRAINFLOW_SOURCE_DIR) / "validation").string();
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One `grainflow validate` invocation: plan (every case built and checked), run, compare, report.
class ValidationRun {
 public:
  ValidationRun(const ValidateOptions& options, std::vector<Item> items, fs::path repository)
      : options_(options), items_(std::move(items)), repository_(std::move(repository)), outcomes_(items_.size()),
        extracted_(items_.size()), failures_(items_.size()), rowsPerItem_(items_.size()) {}

  /// Full mode over all items rewrites docs/validation.md.
  bool writesDocs() const { return !options_.quick && options_.names.empty() && options_.writeDocs; }
  /// Item i runs with its --quick settings: in --quick mode, and in the full report for an item
  /// marked report_quick (its full run takes hours; named on the command line it runs in full).
  bool quickFor(std::size_t i) const { return options_.quick || (options_.names.empty() && items_[i].reportQuick); }

  void plan();
  /// Returns false if interrupted by SIGINT/SIGTERM.
  bool execute();
  void compare();
  void plot();
  int finish();

 private:
  RunOptions runOptions(const PlannedRun& p) const {
    RunOptions r;
    r.threads = options_.threads;
    r.outputDirectory = p.outputDirectory;
    r.overwrite = true;
    r.quiet = true;
    return r;
  }
  PlannedRun planRun(std::size_t i, std::size_t k, const std::string& caseText) const;
  void extractAll(const PlannedRun& p);

  const ValidateOptions& options_;
  std::vector<Item> items_;
  fs::path repository_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::vector<PlannedRun> plan_;
  std::vector<ItemOutcome> outcomes_;
  std::vector<std::vector<std::vector<Extracted>>> extracted_;  // [item][quantity][run]
  std::vector<std::vector<std::string>> failures_;              // [item][run]: divergence messages
  std::vector<std::vector<Row>> rowsPerItem_;
  std::vector<Row> rows_;
  std::vector<std::string> plotSpecs_;
  Provenance provenance_;  // read before the runs: the tree they ran from
};

PlannedRun ValidationRun::planRun(std::size_t i, std::size_t k, const std::string& caseText) const {
  const Item& item = items_[i];
  const bool quick = quickFor(i);
  const auto& runs = item.runsFor(quick);
  PlannedRun p;
  p.item = i;
  p.run = k;
  p.outputDirectory = (fs::path(options_.outputDirectory) / item.name / (runs.size() == 1 ? "run" : fmt::format("run_{}", k))).string();
  fs::create_directories(p.outputDirectory);
  std::vector<Override> overrides = quick ? item.quickOverrides : std::vector<Override>{};
  overrides.insert(overrides.end(), runs[k].overrides.begin(), runs[k].overrides.end());
  p.caseFile = (fs::path(p.outputDirectory) / "case.yaml").string();
  io::writeFileAtomically(p.caseFile, fmt::format("# {} with {} override(s) applied by grainflow validate{}\n{}", item.caseFile,
                                                  overrides.size(), quick ? " --quick" : "",
                                                  applyOverrides(caseText, overrides, item.caseFile)));
  try {
    auto simulation = Simulation::fromFile(p.caseFile, runOptions(p));
    p.steps = std::llround(simulation->settings().endTime / simulation->settings().demStep);
    p.particles = simulation->dem().particles().size();
    p.work = static_cast<double>(p.steps) * (static_cast<double>(p.particles) + 20.0);  // + fixed cost per step
    if (const fluid::Solver* fluid = simulation->fluid())  // a fluid cell step costs about 4 particle steps
      p.work += 4.0 * static_cast<double>(fluid->grid().interiorCellCount()) * static_cast<double>(p.steps) /
                std::max(1, simulation->settings().demStepsPerCouplingStep);
  } catch (const CaseError&) {
    std::fprintf(stderr, "grainflow: validation item '%s' (%s%s) has an invalid case:\n", item.name.c_str(), item.caseFile.c_str(),
                 overrides.empty() ? "" : " with the overrides of validation.yaml");
    throw;
  }
  return p;
}

void ValidationRun::plan() {
  if (writesDocs()) {
    provenance_ = treeProvenance(repository_.string());
    if (!provenance_.changes.empty()) {
      std::printf("note: %zu uncommitted change(s) in %s (first: %s); docs/validation.md will say so. For a report of a "
                  "clean commit, commit them (or run from a clean checkout) and rerun.\n",
                  provenance_.changes.size(), repository_.c_str(), provenance_.changes.front().c_str());
    }
  }
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const Item& item = items_[i];
    const std::size_t runs = item.runsFor(quickFor(i)).size();
    extracted_[i].assign(item.quantities.size(), std::vector<Extracted>(runs));
    failures_[i].assign(runs, "");
    if (options_.quick && item.skipQuick) {
      outcomes_[i].skipped = true;
      continue;
    }
    const std::string caseText = io::readFile(item.caseFile);
    for (std::size_t k = 0; k < runs; ++k) plan_.push_back(planRun(i, k, caseText));
  }
  std::printf("grainflow validate%s: %zu item(s), %zu run(s), %d thread(s), output in %s\n", options_.quick ? " --quick" : "",
              items_.size(), plan_.size(), threadCount(), options_.outputDirectory.c_str());
}

void ValidationRun::extractAll(const PlannedRun& p) {
  const Item& item = items_[p.item];
  for (std::size_t q = 0; q < item.quantities.size(); ++q) try {
      extracted_[p.item][q][p.run] = extract(item.quantities[q], p.outputDirectory);
    } catch (const std::exception& e) {  // unreadable CSV, empty series: this comparison fails, the others go on
      extracted_[p.item][q][p.run].problem = e.what();
    }
}

bool ValidationRun::execute() {
  double totalWork = 0.0, doneWork = 0.0, runWall = 0.0;
  for (const PlannedRun& p : plan_) totalWork += p.work;
  for (std::size_t n = 0; n < plan_.size(); ++n) {
    const PlannedRun& p = plan_[n];
    const Item& item = items_[p.item];
    const double eta = doneWork > 0.0 ? runWall / doneWork * (totalWork - doneWork) : NAN;
    std::printf("[%zu/%zu, %s elapsed, ETA %s] %s: %lld steps, %zu particle(s) ... ", n + 1, plan_.size(),
                formatDuration(secondsSince(start_)).c_str(), formatDuration(eta).c_str(),
                caseLabel(item, item.runsFor(quickFor(p.item))[p.run]).c_str(), p.steps, p.particles);
    std::fflush(stdout);
    const auto runStart = std::chrono::steady_clock::now();
    std::string& failure = failures_[p.item][p.run];
    try {
      auto simulation = Simulation::fromFile(p.caseFile, runOptions(p));
      simulation->prepare();
      if (simulation->run() == RunStatus::Interrupted) {
        std::printf("interrupted\n");
        return false;
      }
    } catch (const DivergenceError& e) {
      failure = e.what();
    }
    const double seconds = secondsSince(runStart);
    runWall += seconds;
    doneWork += p.work;
    outcomes_[p.item].wallSeconds += seconds;
    std::printf("%s in %.2f s\n", failure.empty() ? "done" : "DIVERGED", seconds);
    std::fflush(stdout);
    if (failure.empty()) extractAll(p);
  }
  return true;
}

void ValidationRun::compare() {
  for (std::size_t i = 0; i < items_.size(); ++i) {
    if (outcomes_[i].skipped) continue;
    const Item& item = items_[i];
    const auto& runs = item.runsFor(quickFor(i));
    const std::string itemDirectory = (fs::path(options_.outputDirectory) / item.name).string();
    std::vector<Quantity> quantities;
    std::vector<std::vector<Row>> rowsPerQuantity;
    for (std::size_t q = 0; q < item.quantities.size(); ++q) {
      Quantity quantity = item.quantities[q];
      quantity.tolerance = quantity.toleranceFor(quickFor(i));  // quick_tolerance in --quick mode (and report_quick)
      rowsPerQuantity.push_back(compareQuantity(item, quantity, runs, extracted_[i][q], failures_[i]));
      rowsPerItem_[i].insert(rowsPerItem_[i].end(), rowsPerQuantity.back().begin(), rowsPerQuantity.back().end());
      quantities.push_back(std::move(quantity));
    }
    if (options_.plots)
      outcomes_[i].plots = writeItemPlotSpecs(item, quantities, runs, extracted_[i], rowsPerQuantity, itemDirectory, plotSpecs_);
    rows_.insert(rows_.end(), rowsPerItem_[i].begin(), rowsPerItem_[i].end());
  }
  std::printf("\n%s\n", textTable(rows_).c_str());
  for (std::size_t i = 0; i < items_.size(); ++i)
    if (outcomes_[i].skipped) std::printf("skipped in --quick mode: %s\n", items_[i].name.c_str());
  const std::string resultsFile = (fs::path(options_.outputDirectory) / "results.csv").string();
  io::writeFileAtomically(resultsFile, resultsCsv(rows_));
  std::printf("results: %s\n", resultsFile.c_str());
}

void ValidationRun::plot() {
  if (!options_.plots || plotSpecs_.empty()) return;
  for (const ItemOutcome& o : outcomes_)
    for (const std::string& png : o.plots) fs::remove(png);  // never report a stale figure
  const PlotTool tool = findPlotTool(repository_.string());
  if (!tool.available()) {
    std::printf("plots skipped: %s; %s\n", tool.problem.c_str(), kPlotInstallHint);
    return;
  }
  std::vector<std::string> arguments = {"validation"};
  arguments.insert(arguments.end(), plotSpecs_.begin(), plotSpecs_.end());
  if (runPlotScript(tool, arguments) != 0)
    std::printf("plots: %s failed (the numbers above are unaffected)\n", tool.script.c_str());
  else
    std::printf("plots: %zu PNG(s) in %s/<item>/\n", plotSpecs_.size(), options_.outputDirectory.c_str());
}

int ValidationRun::finish() {
  const double wall = secondsSince(start_);
  if (writesDocs())
    writeDocs(options_.docsDirectory.empty() ? (repository_ / "docs").string() : options_.docsDirectory, repository_.string(), items_,
              rowsPerItem_, outcomes_, wall, threadCount(), provenance_);
  std::size_t passed = 0;
  for (const Row& r : rows_) passed += r.pass() ? 1 : 0;
  std::printf("%zu of %zu comparison(s) passed, %zu failed; wall time %.1f s\n", passed, rows_.size(), rows_.size() - passed, wall);
  return passed == rows_.size() ? kExitOk : kExitValidationFailed;
}

}  // namespace

int runValidate(const ValidateOptions& options) {
  const std::string validationDirectory = options.validationDirectory.empty() ? defaultValidationDirectory() : options.validationDirectory;
  const std::vector<std::string> available = listItems(validationDirectory);
  const std::vector<std::string> selected = options.names.empty() ? available : options.names;
  for (const std::string& name : selected)
    if (std::find(available.begin(), available.end(), name) == available.end()) {
      std::fprintf(stderr, "grainflow: no validation item '%s' in %s (available: %s)\n", name.c_str(), validationDirectory.c_str(),
                   fmt::format("{}", fmt::join(available, ", ")).c_str());
      return kExitUsage;
    }
  if (selected.empty()) {
    std::fprintf(stderr, "grainflow: no validation items in %s\n", validationDirectory.c_str());
    return kExitUsage;
  }
  setThreadCount(options.threads);
  std::vector<Item> items;
  items.reserve(selected.size());
  for (const std::string& name : selected) items.push_back(loadItem((fs::path(validationDirectory) / name).string()));
  ValidationRun run(options, std::move(items), fs::absolute(validationDirectory).lexically_normal().parent_path());
  run.plan();
  if (!run.execute()) return kExitInterrupted;
  run.compare();
  run.plot();
  return run.finish();
}

}  // namespace gf::app
