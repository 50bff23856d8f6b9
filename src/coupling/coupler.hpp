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
// DEM may move, reorder, insert and remove particles in between: the per-particle exchange data
// are columns of the ParticleSet (kBetaColumn, ...), which ParticleSet::gather moves with the
// particles; new particles start from the columns' fill values (they exchange nothing). The
// fields of the FluidView given to computeParticleForces must stay alive, unchanged, until
// fillFluidSources returns (the implicit part and the balance use the fluid velocity).
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
#include "coupling/drag/particle_correction.hpp"
#include "coupling/grid_topology.hpp"
#include "coupling/size_classes.hpp"
#include "coupling/interpolation.hpp"
#include "coupling/stencil.hpp"
#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "dem/particles.hpp"
#include "parallel/decomposition.hpp"

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
  /// Several fluids (fluid.vof): the cells' mixture density and viscosity (seed 002 eqs. 3-4); a
  /// particle's drag, lift, virtual mass and torque take those of its cell instead of the two above.
  /// Null: one fluid.
  const Field* mixtureDensity = nullptr;
  const Field* mixtureViscosity = nullptr;
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

/// Correction applied on top of the drag law (coupling.drag_correction).
enum class DragCorrection { None, Filtered };

/// The filtered drag of Radl & Sundaresan (2014) with the parcel correction (drag/filtered.hpp).
struct FilteredDragSettings {
  double primaryDiameter = 0.0;  // d_prim of L_char, m; 0: Sauter mean of the particles at the first force pass
  double parcelA = 0.0;          // a of c_corr(alpha), seed 003 eq. 3.36
  double parcelK = 0.05;         // k of c_corr(alpha)
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
  bool smoothingAuto = false;    // smoothing_length: auto (seed 003 law, chosen at the first void fraction)
  DragCorrection dragCorrection = DragCorrection::None;
  FilteredDragSettings filteredDrag;
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
  ///
  /// `decomposition`: where the grid and the particles are split among MPI ranks (the fluid
  /// solver's; must outlive the coupler), `grid` is this rank's box and the particle set holds the
  /// rank's own particles plus ghost copies of its neighbours' (ParticleSet::ghost). Then deposits
  /// that fall into ghost cells are summed into their owners' cells (parallel::sumGhosts), the
  /// samples read the neighbours' cells (the FluidView's fields must have their ghost cells across
  /// the cuts filled), smoothing crosses the cuts, ghost particles deposit nothing, and the sums
  /// (particle volume, momentum balance) are over all ranks. nullptr or one rank: the whole grid.
  Coupler(Params& root, const CartesianGrid& grid, const std::array<bool, 3>& periodic, const Vec3& gravity,
          ExchangeModel model = ExchangeModel::A, const parallel::Decomposition* decomposition = nullptr);
  // not copyable: deposit_.blocks points at this coupler's particleBlocks_ (a copy's would point
  // at the original's)
  Coupler(const Coupler&) = delete;
  Coupler& operator=(const Coupler&) = delete;

  /// The columns the coupler adds to the particle set (ParticleSet::addColumn; computeParticleForces
  /// adds them): drag coefficient beta_p (kg/s), slip u_f - u_p (m/s), the exchanged forces besides
  /// the drag (N); with forces.virtual_mass the slip of the previous coupling step (NaN: no
  /// history); with substep_fluid_fields: interpolated the sums over the substeps.
  static constexpr const char* kBetaColumn = "coupling.beta";
  static constexpr const char* kSlipColumn = "coupling.slip";
  static constexpr const char* kOtherForceColumn = "coupling.other_exchanged_force";
  static constexpr const char* kPreviousSlipColumn = "coupling.previous_slip";
  static constexpr const char* kBetaSumColumn = "coupling.beta_sum";
  static constexpr const char* kDragSumColumn = "coupling.drag_sum";
  static constexpr const char* kOtherSumColumn = "coupling.other_sum";
  /// The size class of each particle (index into sizeClasses().diameters(), as a double), written by
  /// sizeStatistics().
  static constexpr const char* kSizeClassColumn = "coupling.size_class";

  void computeVoidFraction(const dem::ParticleSet& particles, CouplingFields& fields);
  void computeParticleForces(const FluidView& fluid, const CouplingFields& fields, dem::ParticleSet& particles);
  void fillFluidSources(const dem::ParticleSet& particles, CouplingFields& fields);
  /// Same, with the set of the last computeParticleForces (or fillFluidSources, computeVoidFraction),
  /// which must still be alive and unchanged (same order).
  void fillFluidSources(CouplingFields& fields);
  /// Forces before every DEM substep (SubstepFluidFields::Interpolated): between
  /// beginSubstepAverage() and endSubstepAverage(), every computeParticleForces adds its
  /// per-particle exchange (beta, drag beta * slip, other exchanged forces) to running sums, the
  /// columns kBetaSumColumn ... of the particle set (the DEM may reorder, insert and remove
  /// particles between substeps: the sums move with them; a particle counts zero for the substeps
  /// it was absent). The end leaves the means over the
  /// substeps as the exchange of the coupling step: the fluid receives sum_s F_s dt_dem over the
  /// interval N dt_dem, the momentum the particles took. One substep: its exchange unchanged.
  void beginSubstepAverage();
  void endSubstepAverage(dem::ParticleSet& particles);

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
  /// beta_p per particle, kg/s, of the set of the last computeParticleForces (its column kBetaColumn).
  const std::vector<double>& dragCoefficients() const;
  /// Slip u_f - u_p per particle at the last computeParticleForces (column kSlipColumn of that set;
  /// after endSubstepAverage the substeps' mean), m/s: the interpolated fluid velocity at a particle
  /// is this plus the particle's velocity at that call. With dragCoefficients() for a semi-implicit
  /// DEM update (implicit_drag.hpp).
  const std::vector<Vec3>& slipVelocities() const;

  /// Coupling-interval criterion for the smallest particle at slip velocity `slip` (seed 000 eq. 5.30).
  CouplingIntervalCheck checkCouplingInterval(double demTimeStep, int demStepsPerFluidStep,
                                              const dem::ParticleSet& particles, const FluidView& fluid,
                                              double slip) const;

  /// Per-cell size statistics of `particles` (size_classes.hpp), computed now: phi_i per class,
  /// the Sauter mean diameter and the mean particle velocity of each cell; writes each particle's
  /// class into column kSizeClassColumn. The force pass computes them itself only for a
  /// polydisperse law; monitors call this when they report per class.
  const CellSizeStatistics& sizeStatistics(dem::ParticleSet& particles);
  const SizeClasses& sizeClasses() const { return sizeClasses_; }
  /// L_char of the filtered drag (m), 0 until the first force pass with drag_correction: filtered.
  double filteredDragLength() const { return filterLength_; }

  const CouplerSettings& settings() const { return settings_; }
  /// Coarse-graining factors per material from the insertions (dem::System::coarseGrainingByMaterial;
  /// 0: none given, coarse_grain_factor applies). Call before the first coupling step.
  void setCoarseGrainingByMaterial(const std::vector<double>& factors) {
    settings_.coarseGraining.setByMaterial(factors);
  }
  const DragLaw& dragLaw() const { return *drag_; }
  const GridTopology& topology() const { return topology_; }
  const ParticleStencils& stencils() const {
    if (!stencilsKept_)
      throw std::logic_error("coupling: the stencils of the last fused deposit were built piece by piece and not kept");
    return stencils_;
  }

  /// State across coupling steps: the previous slip per particle (virtual mass), written with the
  /// particle ids and restored by id into the columns of `particles` (already loaded).
  void save(BinaryWriter& out, const dem::ParticleSet& particles) const;
  void load(BinaryReader& in, dem::ParticleSet& particles);

 private:
  void packSamples(const FluidView& fluid, const CouplingFields& fields, bool planesPerThread);
  /// Packs the interior cells of rows [rowBegin, rowEnd) (row j + n_y k) of the sample channels.
  void packSampleRows(double* out, std::int64_t rowBegin, std::int64_t rowEnd) const;
  /// The cell planes [first, last) that trilinear sampling of particles [begin, end) reads.
  std::pair<int, int> planesSampledBy(const dem::ParticleSet& particles, std::int64_t begin, std::int64_t end) const;
  void scaleToFluxVelocity(const Field& eps);
  static constexpr int kStandardChannels = 10;  // u, eps, grad p, div tau
  /// The columns of `particles` (added if absent): beta, slip, other exchanged force; previous slip
  /// with virtual mass, nullptr otherwise (the substep sums: accumulateSubstep).
  struct Columns {
    double* beta;
    Vec3* slip;
    Vec3* other;
    Vec3* previousSlip;
  };
  template <InterpolationMode Mode, bool StandardChannels, class Law>
  void forcePass(const FluidView& fluid, const Law& law, dem::ParticleSet& particles, const Columns& columns);
  Columns columnsOf(dem::ParticleSet& particles) const;
  /// Whether `particles` carries the exchange columns (computeParticleForces ran on it or a copy).
  static bool carriesExchange(const dem::ParticleSet& particles);
  void keepSlipAsPrevious(dem::ParticleSet& particles) const;
  /// The DEM inserted, removed or reordered particles since the force pass (their columns moved
  /// with them): the force pass's sums no longer apply.
  void followLayout(const dem::ParticleSet& particles);
  void accumulateSubstep(dem::ParticleSet& particles);
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
  static ExchangeData exchangeData(const dem::ParticleSet& particles);
  /// The exchange quantities of particle p that are deposited (see depositExchange).
  template <ExchangeLayout Layout>
  static void exchangeValues(const ExchangeData& data, std::size_t p, double* v);
  /// Calls body(std::integral_constant<ExchangeLayout, L>) with the layout resolved at compile time.
  template <class Body>
  void withExchangeLayout(Body&& body) const;
  void depositExchange(CouplingFields& fields, bool implicit);
  void smoothExchange(CouplingFields& fields, bool implicit) const;
  void updateMomentumBalance(const CouplingFields& fields, bool implicit, std::size_t particleCount);
  /// The ghost cells of f: beyond walls and one-rank periodic sides from this rank's cells, then
  /// (decomposed grid) across the cuts from the neighbours.
  void fillGhosts(Field& f) const;
  /// Decomposed grid: adds the `channels`-interleaved deposit sums in ghost cells (deposit_.merged)
  /// to their owners' cells and zeroes them; one rank: nothing.
  void sumDepositGhosts(int channels);
  /// Under MPI the ghost flags of `particles` (ghosts deposit nothing and count in no sum); nullptr
  /// where every particle is this rank's own.
  const std::uint8_t* ghostFlags(const dem::ParticleSet& particles) const {
    return topology_.distributed() && particles.ghost.size() == particles.size() ? particles.ghost.data() : nullptr;
  }
  /// Under MPI: the primary diameters of every rank that decide the classes (the same on every
  /// rank, the classes of one rank holding every particle). Collective.
  static std::vector<double> diametersOfAllRanks(std::vector<double> local);
  /// Under MPI: the ghost cells' sums of sizeStats_ added to their owners' cells, then the owners'
  /// complete cells copied back into the ghost cells.
  void completeStatisticsAcrossCuts();
  /// Statistics of `particles` into sizeStats_ (classes rebuilt when a diameter is not one of them).
  /// Under MPI each rank sums its own particles, and the cells are completed across the cuts
  /// (completeStatisticsAcrossCuts).
  void updateSizeStatistics(const dem::ParticleSet& particles, bool classVelocities = false);
  /// Adds the fluid-mediated particle-particle friction of the law (yin_sundaresan with
  /// fluid_mediated_friction) to the particles' external forces (not exchanged with the fluid).
  void addFluidMediatedFriction(const FluidView& fluid, const CouplingFields& fields, dem::ParticleSet& particles);
  /// The per-particle drag functor of a polydisperse law or the filtered correction.
  ParticleCorrection particleCorrection(const FluidView& fluid, const dem::ParticleSet& particles);
  /// smoothing_length: auto: the seed's law from the particles present (seed 003 Tab. 4.15, eq. 4.10).
  void chooseSmoothingLength(const dem::ParticleSet& particles);

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
  // the interior rows of cells {first, count} (deposit_.runs holds these on one rank, and also
  // the ghost rows where the grid is decomposed: deposits reach ghost cells there)
  std::vector<std::array<std::size_t, 2>> interiorRuns_;
  std::vector<Field> channelFields_;  // sumDepositGhosts: one deposit channel each
  // The per-particle exchange data (drag force = beta slip, force::drag) are columns of the
  // particle set; the other exchanged force is written only where the exchange reads it (not in
  // the drag-only layout: there it stays all +0, its fill value, the value the force pass would write).
  const dem::ParticleSet* exchangeSet_ = nullptr;  // the set of the last force pass (or deposit since)
  std::uint64_t forceStamp_ = 0;  // its layoutStamp at the force pass (0: none)
  // virtual mass: the layout changed after the force pass, so the previous slip becomes the slip
  // (new particles: 0, not NaN) before the next force pass (done there: the deposits see a const set)
  bool previousSlipFromSlip_ = false;
  double particleVolume_ = 0.0, depositedVolume_ = 0.0, clippedVolume_ = 0.0;
  Vec3 balanceError_;
  bool stencilsReady_ = false, forcesReady_ = false;
  // forces computed, their exchange not yet filled; their exchange deposited by computeVoidFraction
  bool exchangePending_ = false, exchangeDeposited_ = false;
  double exchangedForceScale_ = 0.0;
  // sum over particles of the exchanged force (x, y, z) and of its magnitude, from the force pass
  std::array<double, 4> particleForceSums_{};
  std::vector<std::size_t> particleBlocks_;  // setParticleBlocks
  // substep average (beginSubstepAverage .. endSubstepAverage): sums per particle in the columns
  // kBetaSumColumn, kDragSumColumn, kOtherSumColumn
  bool averaging_ = false;
  int averagedSubsteps_ = 0;
  std::vector<double> volumeSums_;  // per thread, computeVoidFraction
  std::vector<std::array<double, 3>> runSums_;  // per interior row of cells (deposit_.runs)
  bool particleForceSumsValid_ = false;
  // polydisperse laws and the filtered correction (particleCorrection)
  SizeClasses sizeClasses_;
  CellSizeStatistics sizeStats_;
  std::vector<std::size_t> cellOfParticle_;
  std::vector<int> classOfParticle_;
  std::vector<double> sizeRatio_, mixtureReynolds_;
  std::vector<double> parcelCorrectionByMaterial_;  // c_corr(alpha) per material (per-insertion factors)
  std::vector<int> frictionSlot_;     // per cell: its slot in frictionForce_, or -1
  std::vector<Vec3> frictionForce_;   // [slot * classes + i]: friction force density on class i, N/m^3
  double filterLength_ = 0.0;
  bool singleSizeWarned_ = false;
};

}  // namespace gf::coupling
