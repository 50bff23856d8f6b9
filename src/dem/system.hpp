#pragma once
// The DEM half of the solver: particles, materials, walls, contacts, insertion, outlets, integration.
// Contract used by the application loop and the coupling:
//   System(root, domain, gravity)  reads the case sections it owns and inserts the initial particles
//                                  (InitialParticles::FromCheckpoint: none; load() brings them)
//   step(dt)                       one velocity-Verlet step (forces incl. particles().externalForce)
//   checkHealth(step, time)        throws DivergenceError on NaN/Inf or a particle leaving the domain
//   checkTimeStep(dt)              dt against the Rayleigh time (warning > 20 %, error > 50 %)
//   save/load                      complete state (incl. contact history) for bit-identical restarts
//
// Case sections read: materials[], contact, walls[], insertion[], outlets[], neighbour_search
// (see docs/dem.md).
#include <memory>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "core/serialize.hpp"
#include "core/timers.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/contact_kernel.hpp"
#include "dem/insertion/inserter.hpp"
#include "dem/neighbour_list.hpp"
#include "dem/outlet.hpp"
#include "dem/particles.hpp"
#include "dem/periodic_box.hpp"
#include "dem/time_step_check.hpp"
#include "dem/wall_contact_list.hpp"
#include "dem/walls/wall.hpp"
#include "parallel/decomposition.hpp"
#include "parallel/exchange.hpp"

namespace gf::dem {

struct NeighbourSettings {
  double skin = 0.0;          // m; 0 = 0.1 x largest diameter
  int reorderInterval = 20;   // Morton reordering every this many rebuilds (0 = never)
};

/// Load balancing under MPI (case section `parallel`): at the first list build on or after every
/// `interval` steps, when max/mean of the particles the ranks own exceeds `threshold`, the boxes
/// are cut again by recursive coordinate bisection (parallel/rebalance.hpp).
struct BalanceSettings {
  double threshold = 1.2;
  long long interval = 1000;  // steps; 0 = never
  bool byPairs = false;       // weight of a particle: 1 (false) or 1 + its neighbour-list pairs
  double cellCost = 0.0;      // cases with a fluid: a cell's work in particles' worth; 0 = measured
};

struct ContactStatistics {
  long long particleContacts = 0;   // touching particle pairs
  long long wallContacts = 0;       // touching particle-wall primitive pairs
  double coordinationNumber = 0.0;  // 2 particle contacts / particles
  double maxOverlapRatio = 0.0;     // max overlap / radius (particle-particle: / smaller radius)
};

struct EnergyBalance {
  double translational = 0.0;  // J, 1/2 m v^2
  double rotational = 0.0;     // J, 1/2 I w^2
  double gravitational = 0.0;  // J, -m g.x
  double elastic = 0.0;        // J, stored in normal contact springs
  double total() const { return translational + rotational + gravitational + elastic; }
};

/// Whether the constructor inserts the case's initial particles, or leaves the system empty for a
/// restart (load() then brings the particles, lists and inserter states of the checkpoint).
enum class InitialParticles { Insert, FromCheckpoint };

/// Contact history of one particle pair, by particle ids, in the view of particle `a` (the pair's
/// row owner when recorded): what travels with a migrating particle and what a checkpoint holds.
struct PairHistoryRecord {
  std::int64_t a = 0, b = 0;
  Vec3 tangential, rolling;
};
/// Contact history and last force of one particle-wall entry, by particle id and primitive.
struct WallHistoryRecord {
  std::int64_t id = 0;
  std::uint32_t primitive = 0;
  std::uint32_t padding = 0;  // (written to checkpoints: no uninitialised bytes)
  Vec3 tangential, rolling, force, point;
};

class System {
 public:
  /// `decomposition`: under MPI, the rank's box; this rank then owns the particles whose centre
  /// lies in it and keeps ghost copies of its neighbours' particles within contact reach.
  System(Params& root, const Domain& domain, const Vec3& gravity,
         InitialParticles initial = InitialParticles::Insert,
         const parallel::Decomposition& decomposition = parallel::Decomposition());

  void step(double dt);
  /// Throws DivergenceError on NaN/Inf or a particle leaving the domain (collective under MPI:
  /// every rank throws the same error, naming the rank that found it).
  void checkHealth(long long step, double time) const;
  /// dt against the Rayleigh time of the smallest/softest particle present or insertable.
  TimeStepStatus checkTimeStep(double dt) const;

  ParticleSet& particles() { return particles_; }
  const ParticleSet& particles() const { return particles_; }
  const std::vector<Material>& materials() const { return table_.materials(); }
  const ContactTable& contactTable() const { return table_; }
  /// The coarse-graining factor of each material's particles (insertion[].coarse_graining; the
  /// insertions of one material share it), 0 where no insertion gives one.
  std::vector<double> coarseGrainingByMaterial() const;
  /// Rayleigh time of the smallest/softest particle present or that an insertion can make (s);
  /// +inf without either.
  double rayleighTime() const;
  PhaseTimers& timers() { return timers_; }

  /// After editing particles() directly (tests, coupling): rebuilds lists and forces.
  void refresh();
  /// All particles of one radius, mass and type (a monodisperse bed of one material): the contact
  /// sweep and the integration then read these constants of particle 0 only (the same values, the
  /// same results, less memory traffic). Set with the lists; radius, mass and type change only
  /// through insertion, removal or refresh().
  bool identicalSpheres() const { return identicalSpheres_ && identicalSpheresShortcut_; }
  /// Off: the per-particle constants are read for every particle even when identical (tests that
  /// the shortcut changes no bit; measurements).
  void setIdenticalSpheresShortcut(bool enabled) { identicalSpheresShortcut_ = enabled; }

  double time() const { return time_; }
  long long steps() const { return steps_; }
  long long rebuilds() const { return rebuilds_; }
  /// A split of the particles among the threads (BlockSplit of the current lists with equal
  /// shares: size threads + 1; a pure function of the lists, restored by a restart), for particle
  /// loops whose results depend on the split (the coupling's sums). The force loop and the
  /// integration start from it and then follow the threads' measured speeds: their results do
  /// not depend on the split.
  const std::vector<std::size_t>& threadBlocks();
  /// The force loop's split of the last force evaluation (size threads + 1).
  const std::vector<std::size_t>& forceLoopBlocks() const { return buffers_.blockStart; }
  /// Fixes the relative speeds the force loop's split assumes for the threads of a team of
  /// speeds.size() (no more measuring): tests of split independence. Empty: measured again.
  void setThreadSpeeds(const std::vector<double>& speeds);
  const NeighbourList& neighbourList() const { return list_; }
  const WallContactList& wallContacts() const { return wallList_; }
  const std::vector<WallPrimitive>& wallPrimitives() const { return primitives_; }
  const std::vector<Outlet>& outlets() const { return outlets_; }
  /// Force and torque the particles exert on each wall (from the last force evaluation).
  std::vector<WallLoad> wallLoads() const;
  ContactStatistics contactStatistics() const;
  EnergyBalance energy() const;
  std::size_t memoryBytes() const;
  /// Whether the particles are split among MPI ranks (ghosts present, sums reduced over ranks).
  bool distributed() const { return distributed_; }
  const parallel::Decomposition& decomposition() const { return decomposition_; }
  /// parallel.rebalance_*: when to check the balance among the ranks and the threshold.
  const BalanceSettings& balanceSettings() const { return balance_; }
  /// Particles owned by all ranks together (collective under MPI).
  long long globalParticleCount() const;
  /// The particles of every rank, sorted by id, on rank 0 (empty elsewhere; this rank's own
  /// particles on one rank): what output and particle monitors read under MPI. Collective.
  ParticleSet gatherParticles() const;

  /// Complete state in a layout independent of the rank count: particles by id and order key,
  /// contact histories by particle ids. Collective under MPI; only rank 0's writer holds the data.
  void save(BinaryWriter& out) const;
  /// Restores save()'s state on any number of ranks (every rank reads the whole state).
  void load(BinaryReader& in);

 private:
  void readWalls(Params& root);
  /// Under MPI: refuses (domain.decomposition) boxes narrower than the ghosts' reach.
  void checkBoxesHoldTheReach(Params& root) const;
  void updateWalls();
  bool insertAndRemove(double dt);
  bool needsRebuild(double largestMove, double secondLargestMove) const;
  void rebuild(std::vector<std::uint32_t> order, std::size_t listedRows);
  void computeForces(double dt, double halfKick);
  void updateInverseInertia();
  /// The order of the next rebuild: the particles insertAndRemove() kept, or all of them.
  std::vector<std::uint32_t> takePendingOrder();
  /// orderKey = Morton code of the cell of each particle of `subset`.
  void assignMortonKeys(const std::vector<std::uint32_t>& subset, double mortonCell);
  // Single-rank and MPI parts of a rebuild: the order of the arrays and, per new index, the index
  // the particle had before (-1: new here); orderLocally returns whether no particle moved in the arrays.
  bool orderLocally(std::vector<std::uint32_t>& order, bool reorder, double mortonCell,
                    std::vector<std::int64_t>& previous, std::size_t listedRows);
  void migrateAndExchangeGhosts(const std::vector<std::uint32_t>& order, bool reorder, double mortonCell,
                                double ghostReach, std::vector<std::int64_t>& previous, std::size_t listedRows);
  /// Ghost copies of this rank's particles within `reach` of each neighbour's box, appended after
  /// an exchange; the arrays are then sorted by (orderKey, id). Returns the permutation applied.
  std::vector<std::uint32_t> exchangeGhosts(double reach);
  /// Positions and velocities of the ghosts from their owners (every step without a rebuild).
  void forwardGhosts();
  void setHistoriesFromRecords(const std::vector<PairHistoryRecord>& pairs, const std::vector<WallHistoryRecord>& walls,
                               const std::vector<std::uint8_t>& rowsToSet);
  std::vector<PairHistoryRecord> pairRecords(const std::vector<std::uint8_t>& ofParticle) const;
  std::vector<WallHistoryRecord> wallRecords(const std::vector<std::uint8_t>& ofParticle) const;
  /// Load balancing (system_rebalance.cpp): at a list build due for a check (BalanceSettings),
  /// new boxes for the owned particles of `order` when they are out of balance. Returns whether
  /// decomposition_ changed (the migration that follows then sends to any rank).
  bool rebalanceIfDue(const std::vector<std::uint32_t>& order, double reach);
  /// Under MPI: whether the lists are rebuilt this step, the same answer on every rank (one
  /// collective). `localReason`: particles came or went on this rank.
  bool voteForRebuild(bool localReason) const;

  Domain domain_;
  parallel::Decomposition decomposition_;
  bool distributed_ = false;
  // Ghost bookkeeping (MPI): per neighbour rank (decomposition_.neighbourRanks()), the indices of
  // the owned particles sent to it as ghosts and of the ghosts received from it, in message order.
  std::vector<std::vector<std::uint32_t>> ghostSend_, ghostReceive_;
  double ghostReach_ = 0.0;
  BalanceSettings balance_;
  long long balanceChecks_ = -1;  // the last interval (steps_ / balance_.interval) checked
  // Particles that arrived at the last migration (per index, 1 = arrived) and the contact
  // histories they brought: set on their list entries after the build.
  std::vector<std::uint8_t> arrived_;
  std::vector<PairHistoryRecord> arrivedPairs_;
  std::vector<WallHistoryRecord> arrivedWalls_;
  std::vector<std::uint32_t> pendingOrder_;  // set by insertAndRemove() when particles went
  bool hasPendingOrder_ = false;
  PeriodicBox box_;
  Vec3 gravity_;
  ParticleSet particles_;
  ContactTable table_;
  NeighbourSettings neighbour_;
  double skin_ = 0.0;
  NeighbourList list_;
  WallContactList wallList_;
  PartnerBuffers buffers_;
  std::vector<std::size_t> threadBlocks_;  // threadBlocks()
  std::vector<Vec3> positionAtBuild_;
  std::vector<double> inverseMass_, inverseMoment_;  // 1/m, 1/I per particle (updated with the lists)
  bool identicalSpheres_ = false;  // all particles of one radius, mass and type (set with 1/m, 1/I)
  bool identicalSpheresShortcut_ = true;
  double timeAtBuild_ = 0.0;
  long long rebuilds_ = 0;

  // Walls: reference and current primitives, per-wall kinematics.
  std::vector<std::string> wallNames_;
  std::vector<int> wallMaterial_;
  std::vector<WallMotion> wallMotion_;
  std::vector<bool> wallGeometryMoves_;
  std::vector<double> wallReach_;
  std::vector<double> wallActiveUntil_;  // s  // max distance of the wall's geometry from its centre
  std::vector<Vec3> wallVelocity_, wallAngularVelocity_, wallCentre_;
  std::vector<WallPrimitive> referencePrimitives_, primitives_;

  std::vector<std::unique_ptr<Inserter>> inserters_;
  std::vector<Outlet> outlets_;
  std::int64_t nextId_ = 0;
  double time_ = 0.0;
  long long steps_ = 0;
  PhaseTimers timers_;
};

}  // namespace gf::dem
