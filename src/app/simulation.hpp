#pragma once
// A complete run: reads the case, owns the solver parts, advances the coupled time loop,
// writes output, monitors and checkpoints.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "core/monitor.hpp"
#include "core/params.hpp"
#include "core/timers.hpp"
#include "coupling/coupler.hpp"
#include "coupling/fluid_fields_in_time.hpp"
#include "dem/system.hpp"
#include "fluid/solver.hpp"
#include "io/csv_series.hpp"
#include "io/vtk.hpp"
#include "parallel/decomposition.hpp"
#include "resolved/fictitious_domain.hpp"

namespace gf::app {

struct RunOptions {
  int threads = 0;                        // 0 = OpenMP default
  std::optional<std::string> outputDirectory;
  std::optional<double> endTime;          // s, overrides time.end
  std::optional<std::string> restartFile;
  bool overwrite = false;
  bool quiet = false;
};

/// Top-level case keys owned by the application.
struct CaseSettings {
  std::string name;
  Vec3 gravity;
  double endTime = 0.0;             // s
  double demStep = 0.0;             // s
  int demStepsPerCouplingStep = 1;  // DEM substeps per fluid step
  std::string outputDirectory;
  double outputInterval = 0.0;      // s, 0 = no field output
  bool writeParticles = true;
  bool writeFluid = true;
  long long checkpointInterval = 0; // DEM steps, 0 = only on signals and at the end
  double progressInterval = 10.0;   // s of wall time between plain progress lines and monitor CSV writes
  long long healthCheckInterval = 1;

  static CaseSettings read(Params& root, const std::string& caseFile);
};

struct MonitorSlot {
  std::string name;
  double interval = 0.0;  // s
  std::unique_ptr<Monitor> monitor;
  io::CsvSeries series;
};

enum class RunStatus { Finished, Interrupted };

class Simulation {
 public:
  /// Reads and validates the whole case; throws CaseError. Touches no file.
  Simulation(Params& root, const std::string& caseFile, const RunOptions& options);
  ~Simulation();

  /// Loads, validates (including unknown keys) and builds a case from a file.
  static std::unique_ptr<Simulation> fromFile(const std::string& caseFile, const RunOptions& options);

  /// Creates the output directory (refusing to overwrite another run unless allowed) and
  /// restores a checkpoint if one was given. Throws gf::Error with a clear message.
  void prepare();
  /// Runs to the end time (or until SIGINT/SIGTERM, after writing a checkpoint).
  RunStatus run();

  /// One coupling step: fluid -> coupling -> DEM substeps -> coupling -> fluid.
  void advance();

  void writeCheckpoint(const std::string& path) const;
  void restoreCheckpoint(const std::string& path);
  std::string checkpointPath() const;
  std::string lastGoodCheckpoint() const { return lastCheckpoint_; }

  long long step() const { return step_; }
  double time() const { return static_cast<double>(step_) * settings_.demStep; }
  const CaseSettings& settings() const { return settings_; }
  dem::System& dem() { return *dem_; }
  fluid::Solver* fluid() { return fluid_.get(); }
  coupling::Coupler* coupler() { return coupler_.get(); }
  /// Fluid (coupling) time step: DEM step x DEM substeps per coupling step, s.
  double fluidStep() const { return settings_.demStep * settings_.demStepsPerCouplingStep; }
  std::uint64_t caseFingerprint() const { return fingerprint_; }
  /// Every key of the case with its value (defaults filled in) and unit.
  const std::string& resolvedCase() const { return resolvedCaseText_; }
  RunState state() const;
  /// The ranks' layout (one rank without mpirun) and whether this rank writes files and messages.
  const parallel::Decomposition& decomposition() const { return decomposition_; }
  bool rootRank() const { return decomposition_.rank() == 0; }
  /// Wall time per phase for this invocation (simulatedSeconds: physical time it advanced), with
  /// the throughput figures the benchmarks quote (s wall per simulated s, ns per particle-step).
  /// `particles`: the run's particle count (under MPI the caller's globalParticleCount(), a
  /// collective the ranks call together; -1: this rank's particles).
  std::string timingTable(double wallSeconds, double simulatedSeconds, long long particles = -1) const;

 private:
  void writeOutput();
  void sampleMonitors(bool force);
  void flushMonitors();
  /// Health check, checkpoint, monitor files: the state a restart or a divergence falls back to.
  void saveGoodState();
  void checkHealth() const;
  void checkTimeStep(Params& root);
  /// Coupling-interval criterion for the particles present (a warning).
  void checkCouplingInterval();
  coupling::FluidView fluidView();
  void forcesOnParticles(const coupling::FluidView& fluid);  // coupler: fluid forces on the particles
  void initialiseCoupling();
  /// Under MPI: all ranks wait here (directory creation, file writes by rank 0).
  void synchroniseRanks() const;
  /// The state a checkpoint holds (collective under MPI: gathered into rank 0's writer), and its
  /// restore on any layout; `source` names the state in errors.
  void saveState(BinaryWriter& out) const;
  void loadState(BinaryReader& in, const std::string& source);
  /// Coupled cases under MPI (parallel.rebalance_*): at the first coupling step after every
  /// rebalance_interval DEM steps, the work of each rank's box (its cells and particles, weighted
  /// by the measured time per cell and per particle) is compared; above rebalance_threshold x the
  /// mean, the cell cuts of each split axis move to even out the work, and the state moves to the
  /// new boxes (rebalanceTo).
  void rebalanceIfDue();
  /// The run's state carried to the boxes of `next`: saved, sent to every rank, and restored on a
  /// DEM, fluid and coupling built anew for the new boxes (what a restart on another layout does).
  void rebalanceTo(const parallel::Decomposition& next);

  CaseSettings settings_;
  RunOptions options_;
  Domain domain_;
  parallel::Decomposition decomposition_;
  std::unique_ptr<dem::System> dem_;
  std::unique_ptr<fluid::Solver> fluid_;        // absent for DEM-only cases
  std::unique_ptr<coupling::Coupler> coupler_;  // absent without a 'coupling' section
  std::unique_ptr<resolved::FictitiousDomain> resolved_;  // resolved CFD-DEM: absent without a 'resolved' section
  Field fluidVelocity_[3], fluidPressureGradient_[3];  // cell-centred, lent to the coupling
  coupling::FluidFieldsInTime fieldsInTime_;           // substep_fluid_fields: interpolated
  std::vector<MonitorSlot> monitors_;
  std::uint64_t fingerprint_ = 0;
  std::string caseFile_;
  std::string caseText_;  // the case file as read at the start (rebalanceTo builds from it, not from the file now)
  std::string resolvedCaseText_;

  long long step_ = 0;
  long long outputCount_ = 0;
  double nextOutputTime_ = 0.0;
  std::vector<double> nextMonitorTime_;
  std::string lastCheckpoint_;
  io::PvdCollection particleSeries_;
  io::PvdCollection fluidSeries_;
  PhaseTimers appTimers_;
  long long balanceChecks_ = 0;  // rebalanceIfDue: the last interval checked (step_ / rebalance_interval)
  long long runStartStep_ = 0;   // step_ when run() began (0, or the restart's step)
  bool earlyBalanceChecked_ = false;  // rebalanceIfDue's early check (a tenth of an interval in) done
};

/// Case fingerprint: hash of every resolved key except those allowed to change on restart.
std::uint64_t fingerprintOf(const std::vector<ResolvedKey>& keys);
/// The resolved case as YAML-like text "path: value  # unit (default)".
std::string formatResolvedCase(const std::vector<ResolvedKey>& keys);

/// Set by SIGINT/SIGTERM; the loop writes a checkpoint and stops.
void installSignalHandlers();
int pendingSignal();

}  // namespace gf::app
