#pragma once
// Unresolved CFD-DEM coupling: void fraction, fluid forces on particles, exchange fields for the
// fluid. Formulas and model choices: docs/coupling.md. One coupling (fluid) step, in the order of
// Simulation::advance (fluid -> forces -> DEM substeps -> exchange fields -> fluid):
//
//   fluid.step(fields)                                             // uses eps, force density, K, u_p
//   coupler.computeParticleForces(fluidView, fields, particles);   // externalForce/Torque, held over
//   N x dem.step(dt_dem)                                           //   the DEM substeps
//   coupler.computeVoidFraction(particles, fields);                // new stencils and eps (eps_old kept)
//   coupler.fillFluidSources(particles, fields);                   // force density, K, u_p for the fluid
//   coupler.momentumBalanceError();                                // Newton 3: ~1e-16 relative
//
// (computeVoidFraction must also run once before the first computeParticleForces.) The forces of
// computeParticleForces are distributed with the stencils of the latest computeVoidFraction; the
// DEM may move and reorder particles in between (matched by id). The fields of the FluidView given
// to computeParticleForces must stay alive, unchanged, until fillFluidSources returns (the
// implicit part and the balance use the fluid velocity).
#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/coupling_fields.hpp"
#include "core/grid.hpp"
#include "core/params.hpp"
#include "core/serialize.hpp"
#include "coupling/coarse_graining.hpp"
#include "coupling/coupling_interval.hpp"
#include "coupling/deposit.hpp"
#include "coupling/drag/drag_law.hpp"
#include "coupling/grid_topology.hpp"
#include "coupling/interpolation.hpp"
#include "coupling/stencil.hpp"
#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "dem/particles.hpp"

namespace gf::coupling {

/// What the fluid solver lends the coupling (cell-centred fields on the coupling grid). Only the
/// interior cells are read: every stencil, interpolation and derivative maps its cells into the
/// interior (clamped at walls, wrapped at periodic sides), so the ghost layers need not be filled
/// (test FastPaths.FluidViewGhostsAreNeverRead).
struct FluidView {
  const Field* velocity[3] = {nullptr, nullptr, nullptr};          // interstitial fluid velocity, m/s
  const Field* pressureGradient[3] = {nullptr, nullptr, nullptr};  // grad p, Pa/m
  const Field* viscousStressDivergence[3] = {nullptr, nullptr, nullptr};  // div tau, N/m^3 (optional)
  double density = 1000.0;   // kg/m^3
  double viscosity = 1e-3;   // dynamic, Pa s
  double timeStep = 0.0;     // coupling interval (fluid step), s; needed by the virtual mass force
};

enum class ExchangeModel { A, B };
enum class ExchangeScheme { Explicit, SemiImplicit };

struct ForceSwitches {
  bool drag = true;
  bool pressureGradient = true;
  bool viscousStress = true;
  bool buoyancy = false;  // only where the fluid pressure excludes the hydrostatic part
  bool virtualMass = false;
  bool saffmanMeiLift = false;
  bool magnusLift = false;
  bool fluidTorque = false;
  double virtualMassCoefficient = 0.5;
};

/// What the particles see of the fluid over the DEM substeps of one coupling step
/// (coupling.substep_fluid_fields, docs/coupling.md sec. 8).
enum class SubstepFluidFields {
  Held,          // forces once per coupling step, held over the substeps (seed 000 "Base Case", CFDEM)
  Interpolated,  // forces before every substep, fluid fields linear in time (seed 000 "Case II")
};

struct CouplerSettings {
  ExchangeModel model = ExchangeModel::A;  // from the fluid solver (fluid.model), not a coupling key
  std::string dragLaw = "di_felice";
  std::string voidFraction = "divided";
  InterpolationMode interpolation = InterpolationMode::Trilinear;
  bool fluxVelocity = false;  // cell velocity seen by particles from the superficial face flux (coupler.cpp)
  ExchangeScheme exchange = ExchangeScheme::SemiImplicit;
  ForceSwitches forces;
  double smoothingLength = 0.0;  // m; 0 = off
  bool smoothExchangeFields = false;
  double minVoidFraction = 0.1;
  double minRelaxationToIntervalRatio = 10.0;
  CoarseGraining coarseGraining;
  SubstepFluidFields substepFluidFields = SubstepFluidFields::Held;
};

class Coupler {
 public:
  /// Reads section `coupling` of the case. `periodic` as the Domain's, `gravity` for buoyancy,
  /// `model` the fluid's momentum form (fluid.model: A -> -eps grad p, B -> -grad p), which decides
  /// which forces go back to the fluid.
  Coupler(Params& root, const CartesianGrid& grid, const std::array<bool, 3>& periodic, const Vec3& gravity,
          ExchangeModel model = ExchangeModel::A);
  // not copyable: deposit_.blocks points at this coupler's particleBlocks_ (a copy's would point
  // at the original's)
  Coupler(const Coupler&) = delete;
  Coupler& operator=(const Coupler&) = delete;

  void computeVoidFraction(const dem::ParticleSet& particles, CouplingFields& fields);
  void computeParticleForces(const FluidView& fluid, const CouplingFields& fields, dem::ParticleSet& particles);
  void fillFluidSources(const dem::ParticleSet& particles, CouplingFields& fields);
  /// Same, when the particle set is unchanged (same order) since computeParticleForces.
  void fillFluidSources(CouplingFields& fields);
  /// Forces before every DEM substep (SubstepFluidFields::Interpolated): between
  /// beginSubstepAverage() and endSubstepAverage(), every computeParticleForces adds its
  /// per-particle exchange (beta, drag beta * slip, other exchanged forces) to running sums,
  /// matched by particle id (the DEM may reorder, insert and remove particles between substeps;
  /// a particle counts zero for the substeps it was absent). The end leaves the means over the
  /// substeps as the exchange of the coupling step: the fluid receives sum_s F_s dt_dem over the
  /// interval N dt_dem, the momentum the particles took. One substep: its exchange unchanged.
  void beginSubstepAverage();
  void endSubstepAverage(const dem::ParticleSet& particles);

  /// Particles per thread for the particle loops that follow (dem::System::threadBlocks: each
  /// thread then works on the particles whose contacts it computed, in its core's cache). Empty,
  /// or not a split of the current particles for the team: equal blocks. The DEM's split balances
  /// contact work, not particles, while the coupling's passes cost the same per particle: a split
  /// whose largest block holds more than kMaxBlockExcess above an equal share is replaced by
  /// equal blocks (the bubbling bed's split holds 59 % of the particles in one of 2 blocks: its
  /// coupling then waited ~18 % on one thread; equal blocks move ~9 % of the particles to the
  /// other core's cache, which costs less; docs/coupling.md, section 12). The sums over particles
  /// (deposits, momentum balance) follow the split, so it must be a function of the state (as
  /// the DEM's is) for runs to be reproducible.
  static constexpr double kMaxBlockExcess = 0.05;
  void setParticleBlocks(const std::vector<std::size_t>& blocks) {
    particleBlocks_ = nearlyEqual(blocks) ? blocks : std::vector<std::size_t>{};
    deposit_.blocks = &particleBlocks_;
  }
  /// Whether no block of the split holds more than (1 + kMaxBlockExcess) x an equal share.
  static bool nearlyEqual(const std::vector<std::size_t>& blocks) {
    if (blocks.size() < 2) return false;
    const std::size_t team = blocks.size() - 1;
    const double limit = (1.0 + kMaxBlockExcess) * static_cast<double>(blocks.back() - blocks.front()) /
                         static_cast<double>(team);
    for (std::size_t t = 0; t < team; ++t)
      if (blocks[t + 1] < blocks[t] || static_cast<double>(blocks[t + 1] - blocks[t]) > limit) return false;
    return true;
  }

  /// sum over particles of the forces exchanged with the fluid + sum over cells of the fluid
  /// source times cell volume (N); zero up to round-off (Newton's third law), see docs.
  Vec3 momentumBalanceError() const { return balanceError_; }
  /// Sum of |exchanged force| over particles (N), the scale of momentumBalanceError.
  double exchangedForceScale() const { return exchangedForceScale_; }
  double particleVolume() const { return particleVolume_; }     // sum V_p, m^3
  double depositedVolume() const { return depositedVolume_; }   // sum (1 - eps) V_c before clipping, m^3
  double clippedVolume() const { return clippedVolume_; }       // volume lost to min_void_fraction, m^3
  const std::vector<double>& dragCoefficients() const { return beta_; }  // beta_p per particle, kg/s
  /// Slip u_f - u_p per particle at the last computeParticleForces (particle order of that call;
  /// after endSubstepAverage the substeps' mean), m/s: the interpolated fluid velocity at a particle
  /// is this plus the particle's velocity at that call. With dragCoefficients() for a semi-implicit
  /// DEM update (implicit_drag.hpp).
  const std::vector<Vec3>& slipVelocities() const { return slip_; }

  /// Coupling-interval criterion for the smallest particle at slip velocity `slip` (seed 000 eq. 5.30).
  CouplingIntervalCheck checkCouplingInterval(double demTimeStep, int demStepsPerFluidStep,
                                              const dem::ParticleSet& particles, const FluidView& fluid,
                                              double slip) const;

  const CouplerSettings& settings() const { return settings_; }
  const DragLaw& dragLaw() const { return *drag_; }
  const GridTopology& topology() const { return topology_; }
  const ParticleStencils& stencils() const {
    if (!stencilsKept_)
      throw std::logic_error("coupling: the stencils of the last fused deposit were built piece by piece and not kept");
    return stencils_;
  }

  /// State across coupling steps: the previous slip per particle (virtual mass).
  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);

 private:
  void packSamples(const FluidView& fluid, const CouplingFields& fields, bool planesPerThread);
  /// Packs the interior cells of rows [rowBegin, rowEnd) (row j + n_y k) of the sample channels.
  void packSampleRows(double* out, std::int64_t rowBegin, std::int64_t rowEnd) const;
  /// The cell planes [first, last) that trilinear sampling of particles [begin, end) reads.
  std::pair<int, int> planesSampledBy(const dem::ParticleSet& particles, std::int64_t begin, std::int64_t end) const;
  void scaleToFluxVelocity(const Field& eps);
  static constexpr int kStandardChannels = 10;  // u, eps, grad p, div tau
  template <InterpolationMode Mode, bool StandardChannels, class Law>
  void forcePass(const FluidView& fluid, const Law& law, dem::ParticleSet& particles);
  void alignPreviousSlip(const dem::ParticleSet& particles);
  void keepSlipAsPrevious();
  void realignToParticles(const dem::ParticleSet& particles);
  void accumulateSubstep(const dem::ParticleSet& particles);
  void alignSubstepSums(const dem::ParticleSet& particles);
  /// What is deposited per particle for the fluid (see exchangeValues): explicit, every exchanged
  /// force (3); implicit, the explicit part of the exchanged force (3), beta and beta (u_p - u_f@p)
  /// (4); implicit with no exchanged force besides the drag (model A without virtual mass and
  /// lifts, the common case), only beta and beta (u_p - u_f@p): the explicit part is zero.
  enum class ExchangeLayout { Explicit, Implicit, DragOnly };
  static constexpr int channelsOf(ExchangeLayout l) {
    return l == ExchangeLayout::Explicit ? 3 : l == ExchangeLayout::Implicit ? 7 : 4;
  }
  ExchangeLayout exchangeLayout() const;
  /// The per-particle exchange data of the force pass, as plain pointers (read in the deposit
  /// loops, where the vectors' own pointers would be reloaded after every store).
  struct ExchangeData {
    const double* beta;
    const Vec3* slip;
    const Vec3* other;
  };
  ExchangeData exchangeData() const { return {beta_.data(), slip_.data(), otherExchangedForce_.data()}; }
  /// The exchange quantities of particle p that are deposited (see depositExchange).
  template <ExchangeLayout Layout>
  static void exchangeValues(const ExchangeData& data, std::size_t p, double* v);
  /// Calls body(std::integral_constant<ExchangeLayout, L>) with the layout resolved at compile time.
  template <class Body>
  void withExchangeLayout(Body&& body) const;
  void depositExchange(CouplingFields& fields, bool implicit);
  void smoothExchange(CouplingFields& fields, bool implicit) const;
  void updateMomentumBalance(const CouplingFields& fields, bool implicit);
  void fillGhosts(Field& f) const;

  CouplerSettings settings_;
  GridTopology topology_;
  Vec3 gravity_;
  std::unique_ptr<DragLaw> drag_;
  std::unique_ptr<VoidFractionScheme> scheme_;
  ParticleStencils stencils_;
  // A fused deposit that nothing reads the stencils of afterwards builds each piece into its
  // thread's buffer (computeVoidFraction); stencils_ is then sized for the particles but not
  // filled (stencilsKept_ false: stencils() throws, fillFluidSources rebuilds them if it needs them).
  std::vector<ParticleStencils> pieceStencils_;
  bool stencilsKept_ = true;
  FluidView lastFluid_;
  Field solidFraction_;
  Field vorticity_[3];
  Field divTau_[3];
  // fluid fields at cells, channel-interleaved for the particle loop (see packSamples)
  std::vector<double> samples_;
  std::vector<std::vector<double>> threadSamples_;  // per thread: the planes its particles read
  const double* sampleSource_[13] = {};             // the channels' fields (packSamples)
  bool planesPerThread_ = false;
  int sampleChannels_ = 4, gradPChannel_ = -1, divTauChannel_ = -1, vorticityChannel_ = -1;
  DepositBuffers deposit_;
  std::vector<std::size_t> ghostTarget_, ghostSource_;  // ghost cell <- interior cell (fillGhosts)
  // per particle, from computeParticleForces
  // (drag force = beta_ slip_, force::drag)
  // otherExchangedForce_ is written only where the exchange reads it (not in the drag-only
  // layout: there it stays all +0, the value the force pass would write)
  std::vector<Vec3> slip_, otherExchangedForce_;
  std::vector<double> beta_;
  std::vector<std::int64_t> previousId_;
  std::uint64_t previousStamp_ = 0;  // layoutStamp of the set previousId_ was taken from (0: none)
  /// previousId_ was taken from this set as it is now (its layout stamp unchanged).
  bool previousStampMatches(const dem::ParticleSet& particles) const;
  /// Whether previousId_ holds the ids of `particles`, in order: the same layout stamp, else a
  /// full comparison (which then records the stamp).
  bool previousIdsMatch(const dem::ParticleSet& particles);
  /// previousId_ = the ids of `particles` (no copy while the stamp is the same).
  void keepIds(const dem::ParticleSet& particles);
  std::vector<Vec3> previousSlip_;  // NaN where a particle has no history (virtual mass)
  bool previousSlipIsSlip_ = false;  // previousSlip_ is slip_ (not copied without virtual mass)
  double particleVolume_ = 0.0, depositedVolume_ = 0.0, clippedVolume_ = 0.0;
  Vec3 balanceError_;
  bool stencilsReady_ = false, forcesReady_ = false;
  // forces computed, their exchange not yet filled; their exchange deposited by computeVoidFraction
  bool exchangePending_ = false, exchangeDeposited_ = false;
  double exchangedForceScale_ = 0.0;
  // sum over particles of the exchanged force (x, y, z) and of its magnitude, from the force pass
  std::array<double, 4> particleForceSums_{};
  std::vector<std::size_t> particleBlocks_;  // setParticleBlocks
  // substep average (beginSubstepAverage .. endSubstepAverage): sums per particle of averageId_
  bool averaging_ = false;
  int averagedSubsteps_ = 0;
  std::vector<std::int64_t> averageId_;
  std::vector<double> betaSum_;
  std::vector<Vec3> dragSum_, otherSum_;
  std::vector<double> volumeSums_;  // per thread, computeVoidFraction
  std::vector<std::array<double, 3>> runSums_;  // per interior row of cells (deposit_.runs)
  bool particleForceSumsValid_ = false;
};

}  // namespace gf::coupling
