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

namespace gf::dem {

struct NeighbourSettings {
  double skin = 0.0;          // m; 0 = 0.1 x largest diameter
  int reorderInterval = 20;   // Morton reordering every this many rebuilds (0 = never)
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

class System {
 public:
  System(Params& root, const Domain& domain, const Vec3& gravity,
         InitialParticles initial = InitialParticles::Insert);

  void step(double dt);
  void checkHealth(long long step, double time) const;
  /// dt against the Rayleigh time of the smallest/softest particle present or insertable.
  TimeStepStatus checkTimeStep(double dt) const;

  ParticleSet& particles() { return particles_; }
  const ParticleSet& particles() const { return particles_; }
  const std::vector<Material>& materials() const { return table_.materials(); }
  const ContactTable& contactTable() const { return table_; }
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

  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);

 private:
  void readWalls(Params& root);
  void updateWalls();
  bool insertAndRemove(double dt);
  bool needsRebuild(double largestMove, double secondLargestMove) const;
  void rebuild(std::vector<std::uint32_t> order, std::size_t listedRows);
  void computeForces(double dt, double halfKick);
  void updateInverseInertia();

  Domain domain_;
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
