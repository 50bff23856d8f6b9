#include "app/simulation.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <numeric>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>

#include "app/progress.hpp"
#include "core/parallel.hpp"
#include "core/registry.hpp"
#include "core/serialize.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint.hpp"
#include "parallel/environment.hpp"
#include "parallel/exchange.hpp"
#include "parallel/halo.hpp"

namespace gf::app {

namespace fs = std::filesystem;

// ------------------------------------------------------------------ case settings

CaseSettings CaseSettings::read(Params& root, const std::string& caseFile) {
  CaseSettings s;
  Params info = root.section({"case", "-", "name and description of the case"});
  s.name = info.text({"name", "-", "case name (default: file name without extension)"},
                     fs::path(caseFile).stem().string());
  info.text({"description", "-", "free text describing the case"}, "");
  s.gravity = root.vec3({"gravity", "m/s^2", "gravitational acceleration"}, {0.0, 0.0, -9.81});

  Params time = root.requiredSection({"time", "-", "time stepping"});
  s.endTime = time.real({"end", "s", "simulated end time", Range::nonNegative()});
  s.demStep = time.real({"dem_step", "s", "DEM time step (checked against the Rayleigh time)", Range::positive()});
  s.demStepsPerCouplingStep = static_cast<int>(time.integer(
      {"coupling_interval", "-", "DEM steps per fluid (coupling) step", Range::atLeast(1)}, 1));

  Params output = root.section({"output", "-", "field output (VTK) and output directory"});
  s.outputDirectory = output.text({"directory", "-", "output directory (relative to the working directory)"},
                                  "output/" + s.name);
  s.outputInterval = output.real({"interval", "s", "simulated time between VTK outputs; 0 = none", Range::nonNegative()}, 0.0);
  s.writeParticles = output.boolean({"particles", "-", "write particles (.vtu + particles.pvd)"}, true);
  s.writeFluid = output.boolean({"fluid", "-", "write fluid cell fields (.vti + fluid.pvd)"}, true);

  Params checkpoint = root.section({"checkpoint", "-", "restart files"});
  s.checkpointInterval = checkpoint.integer(
      {"interval_steps", "-", "DEM steps between checkpoints; 0 = only at the end and on SIGINT/SIGTERM",
       Range::nonNegative()},
      0);

  Params run = root.section({"run", "-", "run control"});
  s.progressInterval = run.real({"progress_interval", "s",
                                 "wall time between progress lines when not on a terminal; also the longest wait, "
                                 "with or without --quiet, before new monitor rows reach the CSV files",
                                 Range::positive()},
                                10.0);
  s.healthCheckInterval = run.integer(
      {"health_check_interval", "-", "DEM steps between NaN / out-of-domain checks", Range::atLeast(1)}, 1);
  return s;
}

// ------------------------------------------------------------------ fingerprint

std::uint64_t fingerprintOf(const std::vector<ResolvedKey>& unordered) {
  // By path, not in reading order: a run on several ranks reads fluid.cells earlier (for the
  // layout) than one on one rank, and both must restart from each other's checkpoints.
  std::vector<ResolvedKey> keys = unordered;
  std::stable_sort(keys.begin(), keys.end(), [](const ResolvedKey& a, const ResolvedKey& b) { return a.path < b.path; });
  keys.erase(std::unique(keys.begin(), keys.end(), [](const ResolvedKey& a, const ResolvedKey& b) { return a.path == b.path; }),
             keys.end());  // (a key read twice counts once)
  std::uint64_t hash = fnv1a("grainflow-case", 14);
  for (const ResolvedKey& k : keys) {
    const std::string& p = k.path;
    if (p.rfind("output", 0) == 0 || p.rfind("checkpoint", 0) == 0 || p.rfind("monitors", 0) == 0 ||
        p.rfind("run.", 0) == 0 || p == "time.end" || p.rfind("case.description", 0) == 0 ||
        p == "domain.decomposition")  // (a run may continue on another number of ranks)
      continue;
    hash = fnv1a(p.data(), p.size(), hash);
    hash = fnv1a(k.value.data(), k.value.size(), hash);
  }
  return hash;
}

std::string formatResolvedCase(const std::vector<ResolvedKey>& keys) {
  std::string out;
  for (const ResolvedKey& k : keys)
    out += fmt::format("{}: {}{}{}\n", k.path, k.value, k.unit == "-" ? "" : fmt::format("  # [{}]", k.unit),
                       k.fromDefault ? (k.unit == "-" ? "  # (default)" : " (default)") : "");
  return out;
}

// ------------------------------------------------------------------ signals

namespace {
std::atomic<int> gSignal{0};
extern "C" void onSignal(int sig) { gSignal.store(sig); }
}  // namespace

void installSignalHandlers() {
  gSignal.store(0);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
}
int pendingSignal() { return gSignal.load(); }

// ------------------------------------------------------------------ construction

namespace {
/// The ranks' layout: one rank without an MPI launcher (MPI is then not even initialised), else
/// domain.decomposition over the launcher's ranks, cut along the fluid grid's cells if the case
/// has a fluid.
parallel::Decomposition decompositionOf(Params& root, const Domain& domain) {
  if (root.documenting() || !parallel::Environment::launched()) return parallel::Decomposition(domain, {1, 1, 1}, 1, 0);
  const parallel::Environment& env = parallel::Environment::instance();
  if (env.size() == 1) return parallel::Decomposition(domain, {1, 1, 1}, 1, 0);
  std::array<int, 3> cells{0, 0, 0};
  if (root.has("fluid")) {
    Params fluid = root.section({"fluid"});
    const Vec3 n = fluid.vec3({"cells", "-", "grid cells per direction [nx, ny, nz]; nz = 1 is 2D"}, Vec3{16, 16, 16});
    for (int a = 0; a < 3; ++a) cells[a] = std::max(1, static_cast<int>(n[a]));
  }
  parallel::Decomposition d;
  try {
    d = parallel::Decomposition(domain, domain.decomposition, env.size(), env.rank(), cells);
  } catch (const std::invalid_argument& e) {
    root.section({"domain"}).fail("decomposition", e.what(),
                                  fmt::format("auto or [px, py, pz] with px * py * pz = {} ranks", env.size()));
  }
  // A grid axis split among ranks needs the ghost layers plus the shared face in every box
  // (parallel/halo.hpp): refused here, before anything runs.
  using parallel::kMinCellsPerRank;
  if (root.has("fluid"))
    for (int a = 0; a < 3; ++a) {
      if (d.layout()[a] < 2) continue;
      int fewest = cells[a];
      for (int r = 0; r < d.ranks(); ++r) fewest = std::min(fewest, d.cellCount(r)[a]);
      if (fewest < kMinCellsPerRank)
        root.section({"domain"}).fail(
            "decomposition", fmt::format("{} ({} ranks along {} for {} cells: {} cells in the smallest box)",
                                         d.describe(), d.layout()[a], "xyz"[a], cells[a], fewest),
            fmt::format("at least {} cells per rank along a split axis (two ghost layers and the shared face): at most "
                        "{} ranks along {}",
                        kMinCellsPerRank, cells[a] / kMinCellsPerRank, "xyz"[a]));
    }
  return d;
}
}  // namespace

void Simulation::synchroniseRanks() const {
  if (decomposition_.distributed()) (void)parallel::anyOverRanks(false);
}

Simulation::Simulation(Params& root, const std::string& caseFile, const RunOptions& options)
    : options_(options), caseFile_(caseFile) {
  if (std::ifstream in{caseFile}; in) caseText_.assign(std::istreambuf_iterator<char>(in), {});
  settings_ = CaseSettings::read(root, caseFile);
  if (options.endTime) settings_.endTime = *options.endTime;
  if (options.outputDirectory) settings_.outputDirectory = *options.outputDirectory;
  domain_ = Domain::read(root);
  decomposition_ = decompositionOf(root, domain_);
  if (!rootRank()) options_.quiet = true;  // (under MPI only rank 0 prints progress lines)
  // A restart brings its particles from the checkpoint (prepare()): no initial insertion; the
  // coupling-interval check, which needs the particles, runs after the restore.
  const auto initial = options.restartFile ? dem::InitialParticles::FromCheckpoint : dem::InitialParticles::Insert;
  dem_ = std::make_unique<dem::System>(root, domain_, settings_.gravity, initial, decomposition_);
  checkTimeStep(root);
  if (root.documenting() || root.has("fluid"))
    // (resolved CFD-DEM: the fluid solves for the pressure less the hydrostatic part; the bodies get
    // the buoyancy it would give explicitly, src/resolved/fictitious_domain.hpp)
    fluid_ = std::make_unique<fluid::Solver>(root, domain_, root.has("resolved") ? Vec3{} : settings_.gravity,
                                             decomposition_);
  if (root.documenting() || root.has("coupling")) {
    if (!fluid_) root.fail("coupling", "a 'coupling' section without a 'fluid' section", "a 'fluid' section as well");
    const auto model =
        fluid_->model() == fluid::MomentumModel::A ? coupling::ExchangeModel::A : coupling::ExchangeModel::B;
    // (split among the ranks as the fluid's grid, whose boxes the DEM's are)
    coupler_ = std::make_unique<coupling::Coupler>(root, fluid_->grid(), domain_.periodic, settings_.gravity, model,
                                                   &fluid_->decomposition());
    coupler_->setCoarseGrainingByMaterial(dem_->coarseGrainingByMaterial());  // insertion[].coarse_graining
    if (!root.documenting()) initialiseCoupling();
  }
  if (root.documenting() || root.has("resolved")) {  // resolved CFD-DEM (src/resolved)
    if (!fluid_) root.fail("resolved", "a 'resolved' section without a 'fluid' section", "a 'fluid' section as well");
    if (coupler_ && !root.documenting())
      root.fail("resolved", "both a 'coupling' and a 'resolved' section", "one of them (unresolved or resolved CFD-DEM)");
    if (decomposition_.distributed() && root.has("insertion"))  // (fixed bodies alone run on several ranks)
      root.section({"domain"}).fail("decomposition",
                                    fmt::format("{} ranks for a resolved case with particles", decomposition_.ranks()),
                                    "one rank (run without mpirun): resolved particles run on one rank for now");
    resolved_ = std::make_unique<resolved::FictitiousDomain>(root, *fluid_, dem_->particles(), domain_, settings_.gravity,
                                                             &dem_->contactTable());
  }

  for (Params& m : root.list({"monitors", "-", "quantities written as CSV time series (one file per monitor)"})) {
    std::string type = "monitor";
    auto monitor = Registry<Monitor>::instance().create(m, {"type", "-", "monitor type"}, "", &type);
    std::string name = m.text({"name", "-", "file name of the monitor (default: its type)"}, type);
    const double interval = m.real({"interval", "s", "sampling interval; 0 = every coupling step", Range::nonNegative()},
                                   settings_.outputInterval);
    if (root.documenting()) continue;
    for (const MonitorSlot& other : monitors_)
      if (other.name == name) m.fail("name", "'" + name + "' used twice", "a unique monitor name");
    auto columns = monitor->columns();
    monitors_.push_back({name, interval, std::move(monitor),
                         io::CsvSeries((fs::path(settings_.outputDirectory) / (name + ".csv")).string(), columns)});
  }
  nextMonitorTime_.assign(monitors_.size(), 0.0);
  fingerprint_ = fingerprintOf(root.resolved());
  resolvedCaseText_ = formatResolvedCase(root.resolved());
  particleSeries_ = io::PvdCollection((fs::path(settings_.outputDirectory) / "particles.pvd").string());
  fluidSeries_ = io::PvdCollection((fs::path(settings_.outputDirectory) / "fluid.pvd").string());
}

void Simulation::initialiseCoupling() {
  // The first fluid step needs the void fraction of the initial packing, with no d(eps)/dt.
  CouplingFields& fields = fluid_->couplingFields();
  coupler_->computeVoidFraction(dem_->particles(), fields);
  fields.voidFractionOld = fields.voidFraction;
  checkCouplingInterval();
}

void Simulation::checkCouplingInterval() {
  if (dem_->globalParticleCount() == 0) return;  // (collective under MPI, as what follows)
  // Coupling-interval criterion (seed 000 eq. 5.30, tables 5.4/5.5), in the Stokes limit (slip 0).
  const coupling::CouplingIntervalCheck check = coupler_->checkCouplingInterval(
      settings_.demStep, settings_.demStepsPerCouplingStep, dem_->particles(), fluidView(), 0.0);
  if (!check.warning.empty()) spdlog::warn("{}", check.warning);
}

coupling::FluidView Simulation::fluidView() {
  // The coupling reads interior cells only (FluidView, coupler.hpp): no ghost fills; on several
  // ranks also the ghost cells across the cuts, the neighbours' cells (one exchange for the six).
  const auto ghosts = decomposition_.distributed() ? fluid::CellGhosts::Unexchanged : fluid::CellGhosts::Left;
  fluid_->cellVelocity(fluidVelocity_, ghosts);
  fluid_->pressureGradient(fluidPressureGradient_, ghosts);
  if (decomposition_.distributed())
    parallel::fillGhosts({&fluidVelocity_[0], &fluidVelocity_[1], &fluidVelocity_[2], &fluidPressureGradient_[0],
                          &fluidPressureGradient_[1], &fluidPressureGradient_[2]},
                         fluid_->decomposition());
  coupling::FluidView view;
  for (int c = 0; c < 3; ++c) {
    view.velocity[c] = &fluidVelocity_[c];
    view.pressureGradient[c] = &fluidPressureGradient_[c];
  }
  view.density = fluid_->density();
  view.viscosity = fluid_->viscosity();
  if (fluid_->vofEnabled()) {  // (several fluids: each cell's mixture, fluid.vof)
    view.mixtureDensity = &fluid_->mixtureDensity();
    view.mixtureViscosity = &fluid_->mixtureViscosity();
  }
  view.timeStep = fluidStep();
  return view;
}

Simulation::~Simulation() = default;

std::unique_ptr<Simulation> Simulation::fromFile(const std::string& caseFile, const RunOptions& options) {
  Params root = Params::loadFile(caseFile);
  auto simulation = std::make_unique<Simulation>(root, caseFile, options);
  root.checkUnknownKeys();
  return simulation;
}

void Simulation::checkTimeStep(Params& root) {
  if (root.documenting()) return;
  // Rayleigh criterion (e.g. seed 000 lines 957-1000): dt above 20 % of the Rayleigh time is
  // risky, above 50 % the contacts are not resolved. Of the particles present and of the smallest
  // each insertion can make (rate-based ones too; a restart has none before the restore).
  const double rayleigh = dem_->rayleighTime();
  if (!std::isfinite(rayleigh)) return;
  const double ratio = settings_.demStep / rayleigh;
  Params time = root.section({"time"});
  if (ratio > 0.5)
    time.fail("dem_step", fmt::format("{:g} s = {:.0f} % of the Rayleigh time {:.3g} s", settings_.demStep, 100 * ratio, rayleigh),
              fmt::format("at most 50 % of the Rayleigh time (<= {:.3g} s; 10-20 % recommended)", 0.5 * rayleigh));
  if (ratio > 0.2)
    spdlog::warn("time.dem_step = {:g} s is {:.0f} % of the Rayleigh time {:.3g} s (recommended <= 20 %)",
                 settings_.demStep, 100 * ratio, rayleigh);
}

// ------------------------------------------------------------------ output directory and restart

std::string Simulation::checkpointPath() const {
  return (fs::path(settings_.outputDirectory) / "checkpoint.bin").string();
}

void Simulation::prepare() {
  const fs::path dir(settings_.outputDirectory);
  std::error_code ec;
  const bool restarting = options_.restartFile.has_value();
  // (every rank checks before rank 0 creates anything: all stop with the same error, or none)
  const bool taken = fs::exists(dir / "run.yaml", ec);
  synchroniseRanks();
  if (taken && !restarting && !options_.overwrite)
    throw Error(fmt::format("output directory '{}' already holds a run (run.yaml); pass --overwrite to replace it "
                            "or --output to choose another directory",
                            dir.string()));
  if (rootRank()) fs::create_directories(decomposition_.distributed() ? dir / "pieces" : dir, ec);
  synchroniseRanks();
  if (ec || !fs::is_directory(dir))
    throw Error(fmt::format("output directory '{}' cannot be created: {}", dir.string(),
                            ec ? ec.message() : "a file of that name exists"));
  if (::access(dir.c_str(), W_OK) != 0)
    throw Error(fmt::format("output directory '{}' is not writable", dir.string()));
  if (restarting) {
    restoreCheckpoint(*options_.restartFile);
  } else if (options_.overwrite && rootRank()) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string ext = entry.path().extension().string();
      if (ext == ".vtu" || ext == ".vti" || ext == ".pvtu" || ext == ".pvti" || ext == ".pvd" || ext == ".csv" ||
          ext == ".bin")
        fs::remove(entry.path());
    }
    if (fs::is_directory(dir / "pieces", ec))
      for (const auto& entry : fs::directory_iterator(dir / "pieces")) fs::remove(entry.path());
  }
  if (rootRank())
    io::writeFileAtomically((dir / "run.yaml").string(),
                            fmt::format("# grainflow resolved case ({}), every key with its value and unit\n{}",
                                        caseFile_, resolvedCaseText_));
  synchroniseRanks();
}

void Simulation::writeCheckpoint(const std::string& path) const {
  BinaryWriter out;
  saveState(out);
  // (the state is gathered on rank 0, which writes the one file; the others wait for it)
  if (rootRank()) io::writeCheckpoint(path, fingerprint_, out);
  synchroniseRanks();
}

void Simulation::saveState(BinaryWriter& out) const {
  out.put(step_);
  out.put(outputCount_);
  out.put(nextOutputTime_);
  out.putVector(nextMonitorTime_);
  dem_->save(out);
  if (fluid_) fluid_->save(out);
  if (coupler_) coupler_->save(out, dem_->particles());
  if (resolved_) resolved_->save(out, dem_->particles());
  for (const MonitorSlot& m : monitors_) m.monitor->save(out);
}

void Simulation::restoreCheckpoint(const std::string& path) {
  const std::vector<char> payload = io::readCheckpoint(path, fingerprint_);
  BinaryReader in(payload.data(), payload.size());
  loadState(in, "checkpoint '" + path + "'");
  if (coupler_) checkCouplingInterval();
  if (rootRank()) {
    particleSeries_.load();
    particleSeries_.truncateAfter(time());
    fluidSeries_.load();
    fluidSeries_.truncateAfter(time());
    for (MonitorSlot& m : monitors_) m.series.resumeFrom(time());
  }
  synchroniseRanks();
  lastCheckpoint_ = path;
}

void Simulation::loadState(BinaryReader& in, const std::string& source) {
  step_ = in.get<long long>();
  outputCount_ = in.get<long long>();
  nextOutputTime_ = in.get<double>();
  nextMonitorTime_ = in.getVector<double>();
  if (nextMonitorTime_.size() != monitors_.size())
    throw CheckpointError(fmt::format("{} has {} monitors, the case has {}", source, nextMonitorTime_.size(),
                                      monitors_.size()));
  dem_->load(in);
  if (fluid_) fluid_->load(in);
  if (coupler_) {
    coupler_->load(in, dem_->particles());
    // Rebuild the coupling stencils of the restored particles without touching the restored fields.
    CouplingFields& fields = fluid_->couplingFields();
    const Field eps = fields.voidFraction, epsOld = fields.voidFractionOld;
    coupler_->computeVoidFraction(dem_->particles(), fields);
    fields.voidFraction = eps;
    fields.voidFractionOld = epsOld;
  }
  if (resolved_) resolved_->load(in, dem_->particles());
  for (MonitorSlot& m : monitors_) m.monitor->load(in);
  if (!in.atEnd()) throw CheckpointError(fmt::format("{} has trailing data (written by another case?)", source));
}

// ------------------------------------------------------------------ load balancing (coupled cases)

void Simulation::rebalanceIfDue() {
  // (coupled cases under MPI on the Cartesian layout; DEM-only cases re-cut their own boxes, dem::System)
  if (!coupler_ || !decomposition_.distributed() || !decomposition_.gridded()) return;
  const dem::BalanceSettings& b = dem_->balanceSettings();
  if (b.interval <= 0) return;
  // Besides every interval, one early check a tenth of an interval after the run (or the restart)
  // began: a case that starts badly cut (a settled bed under a layout that cuts across its
  // height) is re-cut after a few measured steps instead of running a whole interval unbalanced.
  const bool early = !earlyBalanceChecked_ && step_ - runStartStep_ >= std::max(1LL, b.interval / 10);
  if (!early && step_ / b.interval <= balanceChecks_) return;
  earlyBalanceChecked_ = earlyBalanceChecked_ || early;
  balanceChecks_ = step_ / b.interval;
  // The work of a box: its cells at the measured fluid time per cell plus its particles at the
  // measured particle time (DEM and coupling) per particle, both summed over the ranks since the
  // start (waits in collectives and ghost exchanges excluded where the timers separate them).
  const fluid::Solver& f = *fluid_;
  const CartesianGrid& whole = f.globalGrid();
  const PhaseTimers& d = dem_->timers();
  const double particleSeconds = d.seconds(Phase::NeighbourSearch) + d.seconds(Phase::Contacts) +
                                 d.seconds(Phase::Integration) + appTimers_.seconds(Phase::Coupling);
  const double fluidSeconds = fluid_->timers().seconds(Phase::Fluid);
  // per axis, the owned particles in each global cell plane (one allreduce for the three axes)
  std::vector<double> local(static_cast<std::size_t>(whole.cells[0] + whole.cells[1] + whole.cells[2]) + 4, 0.0);
  const dem::ParticleSet& p = dem_->particles();
  long long owned = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.isGhost(i)) continue;
    ++owned;
    std::size_t base = 0;
    for (int a = 0; a < 3; ++a) {
      const int plane = std::clamp(static_cast<int>(std::floor((p.position[i][a] - whole.origin[a]) / whole.spacing[a])),
                                   0, whole.cells[a] - 1);
      local[base + static_cast<std::size_t>(plane)] += 1.0;
      base += static_cast<std::size_t>(whole.cells[a]);
    }
  }
  const std::size_t extra = local.size() - 4;
  local[extra] = particleSeconds;
  local[extra + 1] = fluidSeconds;
  local[extra + 2] = static_cast<double>(f.grid().interiorCellCount());
  local[extra + 3] = static_cast<double>(owned);
  const std::vector<double> sums = parallel::sumOverRanks(local);
  const double particles = sums[extra + 3], cells = sums[extra + 2];
  // (parallel.rebalance_cell_cost > 0: a cell weighs that many particles, measured times not used)
  const bool given = b.cellCost > 0.0;
  const double perParticle = given ? 1.0 : particles > 0.0 ? sums[extra] / particles : 0.0;
  const double perCell = given ? b.cellCost : cells > 0.0 ? sums[extra + 1] / cells : 0.0;
  const std::vector<double> work =
      parallel::allgather(perCell * local[extra + 2] + perParticle * local[extra + 3]);
  const double mean = std::accumulate(work.begin(), work.end(), 0.0) / static_cast<double>(work.size());
  const double before = mean > 0.0 ? *std::max_element(work.begin(), work.end()) / mean : 1.0;
  if (!(before > b.threshold)) return;
  // New cuts per split axis: the planes' work (their cells and particles) in even shares.
  std::array<std::vector<int>, 3> cuts = decomposition_.cellCuts();
  std::array<std::vector<double>, 3> planeWork;
  int splitAxes = 0, axis = 0;
  std::size_t base = 0;
  for (int a = 0; a < 3; ++a) {
    const int n = whole.cells[a];
    if (decomposition_.layout()[a] > 1) {
      std::vector<double>& work = planeWork[static_cast<std::size_t>(a)];
      for (int c = 0; c < n; ++c) work.push_back(perCell * cells / n + perParticle * sums[base + static_cast<std::size_t>(c)]);
      cuts[static_cast<std::size_t>(a)] =
          parallel::Decomposition::balancedCuts(work, decomposition_.layout()[a], parallel::kMinCellsPerRank);
      ++splitAxes, axis = a;
    }
    base += static_cast<std::size_t>(n);
  }
  // With one split axis the work of the new boxes is known from the planes: a re-cut that would
  // not lower the imbalance by a per cent (whole planes are too coarse) is not made.
  double after = 0.0;
  if (splitAxes == 1) {
    const std::vector<int>& c = cuts[static_cast<std::size_t>(axis)];
    const std::vector<double>& work = planeWork[static_cast<std::size_t>(axis)];
    double largest = 0.0, total = 0.0;
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      const double part = std::accumulate(work.begin() + c[k], work.begin() + c[k + 1], 0.0);
      largest = std::max(largest, part);
      total += part;
    }
    after = largest / (total / static_cast<double>(c.size() - 1));
  }
  if (cuts == decomposition_.cellCuts() || (splitAxes == 1 && after > 0.99 * before)) {
    if (rootRank())
      spdlog::info("parallel: imbalance {:.3f} at t = {:g} s, boxes kept (whole cell planes allow no better)", before,
                   time());
    return;
  }
  long long moved = 0;  // cells whose rank changes
  const parallel::Decomposition next = decomposition_.withCellCuts(cuts);
  for (int r = 0; r < decomposition_.ranks(); ++r) {
    const auto o0 = decomposition_.cellOffset(r), n0 = decomposition_.cellCount(r);
    const auto o1 = next.cellOffset(r), n1 = next.cellCount(r);
    long long kept = 1;
    for (int a = 0; a < 3; ++a) kept *= std::max(0, std::min(o0[a] + n0[a], o1[a] + n1[a]) - std::max(o0[a], o1[a]));
    moved += static_cast<long long>(n0[0]) * n0[1] * n0[2] - kept;
  }
  rebalanceTo(next);
  if (rootRank()) {
    std::string described;
    for (int a = 0; a < 3; ++a)
      if (next.layout()[a] > 1) described += fmt::format(" {}: {}", "xyz"[a], fmt::join(next.cellCuts()[static_cast<std::size_t>(a)], " "));
    spdlog::info("parallel: imbalance {:.3f} at t = {:g} s: boxes re-cut along the cells ({:.0f} % of the cells moved; "
                 "cell cuts{})",
                 before, time(), 100.0 * static_cast<double>(moved) / cells, described);
  }
}

void Simulation::rebalanceTo(const parallel::Decomposition& next) {
  BinaryWriter out;
  saveState(out);  // (gathered into rank 0's writer)
  const parallel::Bytes state = parallel::broadcastFromRoot(parallel::Bytes(out.bytes().begin(), out.bytes().end()));
  const PhaseTimers demTimers = dem_->timers(), fluidTimers = fluid_->timers();
  decomposition_ = next;
  // the DEM, the fluid and the coupling built for the new boxes, as for a restart
  // (the case as it was read at the start: the file may have been edited since)
  Params root = caseText_.empty() ? Params::loadFile(caseFile_) : Params::loadString(caseText_, caseFile_);
  dem_ = std::make_unique<dem::System>(root, domain_, settings_.gravity, dem::InitialParticles::FromCheckpoint,
                                       decomposition_);
  fluid_ = std::make_unique<fluid::Solver>(root, domain_, settings_.gravity, decomposition_);
  const auto model =
      fluid_->model() == fluid::MomentumModel::A ? coupling::ExchangeModel::A : coupling::ExchangeModel::B;
  coupler_ = std::make_unique<coupling::Coupler>(root, fluid_->grid(), domain_.periodic, settings_.gravity, model,
                                                 &fluid_->decomposition());
  coupler_->setCoarseGrainingByMaterial(dem_->coarseGrainingByMaterial());
  for (int ph = 0; ph < static_cast<int>(Phase::Count); ++ph) {  // (the run's timing table goes on)
    dem_->timers().add(static_cast<Phase>(ph), demTimers.seconds(static_cast<Phase>(ph)));
    fluid_->timers().add(static_cast<Phase>(ph), fluidTimers.seconds(static_cast<Phase>(ph)));
  }
  BinaryReader in(state.data(), state.size());
  loadState(in, "the state moved to the new boxes");
}

// ------------------------------------------------------------------ the time loop

void Simulation::advance() {
  // One coupling step. Data flows one way (seed 000, unresolved CFD-DEM algorithm; seed 001,
  // coupling scheme): fluid -> coupling (forces on particles) -> DEM substeps -> coupling (void
  // fraction and exchange fields) -> fluid. The fluid step uses the exchange fields of the
  // previous coupling step; the particles feel the fluid it just produced: once, held over the
  // substeps, or (substep_fluid_fields: interpolated) before every substep, the fluid linear in
  // time between its previous and its new state (coupling/fluid_fields_in_time.hpp).
  const bool everySubstep =
      coupler_ && coupler_->settings().substepFluidFields == coupling::SubstepFluidFields::Interpolated;
  if (everySubstep) {
    ScopedPhase timer(appTimers_, Phase::Coupling);
    fieldsInTime_.keepStart(fluidView());
  }
  if (resolved_)  // the fluid step with the bodies' forcing; their loads onto the particles (src/resolved)
    resolved_->fluidStep(*fluid_, dem_->particles(), fluidStep());
  else if (fluid_)
    fluid_->step(fluidStep());
  coupling::FluidView fluidNow;
  if (coupler_) {
    ScopedPhase timer(appTimers_, Phase::Coupling);
    fluidNow = fluidView();
  }
  if (coupler_ && !everySubstep) forcesOnParticles(fluidNow);
  if (everySubstep) coupler_->beginSubstepAverage();
  const int substeps = settings_.demStepsPerCouplingStep;
  for (int s = 0; s < substeps; ++s) {
    if (everySubstep) forcesOnParticles(fieldsInTime_.at(fluidNow, (s + 1.0) / substeps, settings_.demStep));
    if (resolved_) resolved_->beforeDemStep(dem_->particles(), settings_.demStep, dem_->wallPrimitives());
    dem_->step(settings_.demStep);
  }
  if (coupler_) {
    ScopedPhase timer(appTimers_, Phase::Coupling);
    if (everySubstep) coupler_->endSubstepAverage(dem_->particles());  // the substeps' mean exchange
    coupler_->setParticleBlocks(dem_->threadBlocks());  // (the DEM steps may have rebuilt the lists)
    coupler_->computeVoidFraction(dem_->particles(), fluid_->couplingFields());
    coupler_->fillFluidSources(dem_->particles(), fluid_->couplingFields());
  }
  step_ += substeps;
}

void Simulation::forcesOnParticles(const coupling::FluidView& fluid) {
  ScopedPhase timer(appTimers_, Phase::Coupling);
  coupler_->setParticleBlocks(dem_->threadBlocks());  // the DEM's split where it is nearly even
  coupler_->computeParticleForces(fluid, fluid_->couplingFields(), dem_->particles());
}

RunState Simulation::state() const {
  return RunState{time(), step_, dem_.get(), fluid_.get(), coupler_.get(), settings_.gravity, nullptr, resolved_.get()};
}

void Simulation::checkHealth() const {
  dem_->checkHealth(step_, time());  // (collective under MPI)
  if (!fluid_) return;
  if (!decomposition_.distributed()) {
    fluid_->checkHealth(step_, time());
    return;
  }
  // The fluid checks its own box: every rank learns whether any rank found a problem, and all stop
  // with the message of the lowest such rank, naming it.
  std::string message;
  try {
    fluid_->checkHealth(step_, time());
  } catch (const DivergenceError& e) {
    message = e.what();
  }
  if (!parallel::anyOverRanks(!message.empty())) return;
  const std::vector<parallel::Bytes> all = parallel::allgather(parallel::Bytes(message.begin(), message.end()));
  for (std::size_t r = 0; r < all.size(); ++r)
    if (!all[r].empty())
      throw DivergenceError(step_, fmt::format("{} (rank {})", std::string(all[r].begin(), all[r].end()), r));
}

void Simulation::writeOutput() {
  ScopedPhase timer(appTimers_, Phase::Output);
  const fs::path dir(settings_.outputDirectory);
  if (settings_.writeParticles) {
    const std::string file = fmt::format("particles_{:06d}.vtu", outputCount_);
    if (decomposition_.distributed()) {
      // Each rank writes its own particles (pieces/particles_<output>_<rank>.vtu); rank 0 writes the
      // .pvtu that binds them, which the .pvd series lists: ParaView opens one data set.
      const int ranks = decomposition_.ranks();
      auto pieceName = [&](int rank) { return fmt::format("pieces/particles_{:06d}_{:04d}.vtu", outputCount_, rank); };
      const dem::ParticleSet& p = dem_->particles();
      dem::ParticleSet owned = p;
      std::vector<std::uint32_t> mine;
      for (std::size_t i = 0; i < p.size(); ++i)
        if (!p.isGhost(i)) mine.push_back(static_cast<std::uint32_t>(i));
      owned.gather(mine);
      io::writeFileAtomically((dir / pieceName(decomposition_.rank())).string(), io::particlesVtu(owned));
      const std::string parallelFile = fmt::format("particles_{:06d}.pvtu", outputCount_);
      if (rootRank()) {
        std::vector<std::string> pieces;
        for (int r = 0; r < ranks; ++r) pieces.push_back(pieceName(r));
        io::writeFileAtomically((dir / parallelFile).string(), io::particlesPvtu(pieces));
        particleSeries_.add(time(), parallelFile);
      }
    } else {
      io::writeFileAtomically((dir / file).string(), io::particlesVtu(dem_->particles()));
      particleSeries_.add(time(), file);
    }
  }
  if (fluid_ && settings_.writeFluid) {
    const std::string file = fmt::format("fluid_{:06d}.vti", outputCount_);
    std::vector<io::VtkArray> arrays;
    for (const fluid::NamedCellField& f : fluid_->cellFields()) arrays.push_back(io::cellArray(f.name, f.field));
    if (decomposition_.distributed()) {
      // Each rank its box of cells as a piece in the whole grid's index space; rank 0 the .pvti.
      const parallel::Decomposition& d = fluid_->decomposition();
      const CartesianGrid& local = fluid_->grid();
      CartesianGrid whole = local;
      whole.origin = domain_.min;
      for (int a = 0; a < 3; ++a)
        whole.cells[a] = static_cast<int>(std::lround((domain_.max[a] - domain_.min[a]) / local.spacing[a]));
      auto pieceName = [&](int rank) { return fmt::format("pieces/fluid_{:06d}_{:04d}.vti", outputCount_, rank); };
      io::writeFileAtomically((dir / pieceName(d.rank())).string(),
                              io::cellFieldsVtiPiece(local, d.cellOffset(), whole, arrays));
      if (rootRank()) {
        std::vector<std::string> pieces;
        std::vector<std::array<int, 6>> extents;
        for (int r = 0; r < d.ranks(); ++r) {
          const auto o = d.cellOffset(r), n = d.cellCount(r);
          pieces.push_back(pieceName(r));
          extents.push_back({o[0], o[0] + n[0], o[1], o[1] + n[1], o[2], o[2] + n[2]});
        }
        const std::string parallelFile = fmt::format("fluid_{:06d}.pvti", outputCount_);
        io::writeFileAtomically((dir / parallelFile).string(), io::cellFieldsPvti(whole, pieces, extents, arrays));
        fluidSeries_.add(time(), parallelFile);
      }
    } else {
      io::writeFileAtomically((dir / file).string(), io::cellFieldsVti(fluid_->grid(), arrays));
      fluidSeries_.add(time(), file);
    }
  }
  ++outputCount_;
  nextOutputTime_ = static_cast<double>(outputCount_) * settings_.outputInterval;
}

void Simulation::sampleMonitors(bool force) {
  ScopedPhase timer(appTimers_, Phase::Output);
  RunState s = state();
  // Under MPI every rank samples (the DEM's sums are collective) and rank 0 writes the rows;
  // monitors that loop over particles read the particles gathered on rank 0.
  dem::ParticleSet gathered;
  if (decomposition_.distributed()) {
    bool due = false, particlesRead = false;  // (the same answer on every rank: times and types only)
    for (std::size_t m = 0; m < monitors_.size(); ++m)
      if (force || s.time + 0.5 * settings_.demStep >= nextMonitorTime_[m]) {
        due = true;
        particlesRead = particlesRead || monitors_[m].monitor->readsParticles();
      }
    if (!due) return;
    if (particlesRead) gathered = dem_->gatherParticles();
    s.particles = &gathered;  // (empty where no due monitor reads them)
  }
  const double tolerance = 0.5 * settings_.demStep;
  for (std::size_t m = 0; m < monitors_.size(); ++m) {
    if (!force && s.time + tolerance < nextMonitorTime_[m]) continue;
    for (const std::vector<double>& row : monitors_[m].monitor->sampleRows(s))
      if (rootRank()) monitors_[m].series.addRow(s.time, row);
    const double interval = monitors_[m].interval;
    nextMonitorTime_[m] = interval > 0.0 ? (std::floor((s.time + tolerance) / interval) + 1.0) * interval : 0.0;
  }
}

void Simulation::saveGoodState() {
  // Only a state that passed the health check becomes a checkpoint: after a divergence the last
  // checkpoint is still a good one.
  checkHealth();
  ScopedPhase timer(appTimers_, Phase::Output);
  // Monitor rows first, so that the CSVs on disk always reach the time of the checkpoint on disk: a
  // restart keeps their rows up to that time and drops the later ones (CsvSeries::resumeFrom).
  flushMonitors();
  writeCheckpoint(checkpointPath());
  lastCheckpoint_ = checkpointPath();
}

void Simulation::flushMonitors() {
  if (!rootRank()) return;
  for (MonitorSlot& m : monitors_) m.series.flush();
}

RunStatus Simulation::run() {
  installSignalHandlers();
  const long long totalSteps = std::llround(settings_.endTime / settings_.demStep);
  ProgressReporter progress(settings_.endTime, settings_.progressInterval, options_.quiet);
  runStartStep_ = step_;
  // (a restart's first balance check is the early one below, after some measured steps)
  if (const long long interval = dem_->balanceSettings().interval; interval > 0) balanceChecks_ = step_ / interval;
  if (step_ == 0) {
    checkHealth();
    sampleMonitors(true);
    if (settings_.outputInterval > 0.0) writeOutput();
  }
  // The monitor CSVs follow the run: written now (on a restart, without the rows the run wrote
  // after its checkpoint, which it samples again), then at least every progress_interval of wall
  // time and with each checkpoint, so a user watching a long run, or one whose run dies, has the
  // rows up to a few seconds ago. Each write is atomic (io/csv_series.hpp).
  flushMonitors();
  WallClockInterval monitorWrites(settings_.progressInterval);
  long long nextCheckpointStep =
      settings_.checkpointInterval > 0 ? (step_ / settings_.checkpointInterval + 1) * settings_.checkpointInterval : -1;
  const double outputTolerance = 0.5 * settings_.demStep;

  while (step_ < totalSteps) {
    advance();
    if (step_ % settings_.healthCheckInterval == 0) checkHealth();
    rebalanceIfDue();
    sampleMonitors(false);
    if (settings_.outputInterval > 0.0 && time() + outputTolerance >= nextOutputTime_) writeOutput();
    if (nextCheckpointStep > 0 && step_ >= nextCheckpointStep) {
      saveGoodState();
      nextCheckpointStep += settings_.checkpointInterval;
    }
    // (under MPI a signal may reach the ranks at different steps: they stop together, at the
    // first multiple of kSignalCheckSteps coupling steps after any rank saw one; a collective
    // every step would cost a few per cent of a DEM step)
    constexpr long long kSignalCheckSteps = 16;
    const bool signalled = decomposition_.distributed()
                               ? (step_ / settings_.demStepsPerCouplingStep) % kSignalCheckSteps == 0 &&
                                     parallel::anyOverRanks(pendingSignal() != 0)
                               : pendingSignal() != 0;
    if (signalled) {
      saveGoodState();
      progress.finish(time());
      return RunStatus::Interrupted;
    }
    progress.update(time(), step_);
    if (monitorWrites.due()) {
      ScopedPhase timer(appTimers_, Phase::Output);
      flushMonitors();
    }
  }
  saveGoodState();
  progress.finish(time());
  return RunStatus::Finished;
}

// ------------------------------------------------------------------ report

std::string Simulation::timingTable(double wallSeconds, double simulatedSeconds, long long particles) const {
  PhaseTimers total = dem_->timers();
  total.add(Phase::Output, appTimers_.seconds(Phase::Output));
  total.add(Phase::Coupling, appTimers_.seconds(Phase::Coupling));
  if (fluid_) {
    // The fluid's own total includes its pressure solves; show them apart.
    const PhaseTimers& f = fluid_->timers();
    total.add(Phase::Fluid, f.seconds(Phase::Fluid) - f.seconds(Phase::PressureSolve));
    total.add(Phase::PressureSolve, f.seconds(Phase::PressureSolve));
  }
  std::string out = fmt::format("{:<18} {:>10} {:>7}\n", "phase", "wall [s]", "share");
  double accounted = 0.0;
  for (int p = 0; p < static_cast<int>(Phase::Count); ++p) {
    const double s = total.seconds(static_cast<Phase>(p));
    accounted += s;
    out += fmt::format("{:<18} {:>10.3f} {:>6.1f}%\n", kPhaseNames[p], s, wallSeconds > 0 ? 100.0 * s / wallSeconds : 0.0);
  }
  const double other = std::max(0.0, wallSeconds - accounted);
  out += fmt::format("{:<18} {:>10.3f} {:>6.1f}%\n", "other", other, wallSeconds > 0 ? 100.0 * other / wallSeconds : 0.0);
  out += fmt::format("{:<18} {:>10.3f}\n", "total", wallSeconds);
  if (simulatedSeconds > 0.0) {
    const double count = particles >= 0 ? static_cast<double>(particles) : static_cast<double>(dem_->particles().size());
    const double particleSteps = count * simulatedSeconds / settings_.demStep;
    out += fmt::format("throughput         {:.4g} s wall per simulated second", wallSeconds / simulatedSeconds);
    if (particleSteps > 0.0) out += fmt::format(", {:.4g} ns per particle-step (all phases)", 1e9 * wallSeconds / particleSteps);
    out += "\n";
  }
  return out;
}

}  // namespace gf::app
