#pragma once
// Particle storage: structure of arrays (one contiguous array per quantity), so that kernels
// stream through memory, vectorise, and port to a GPU unchanged.
#include <cstdint>
#include <string>
#include <vector>

#include "core/serialize.hpp"
#include "core/vec3.hpp"

namespace gf::dem {

struct ParticleSet {
  std::vector<std::int64_t> id;       // unique, stable across reordering and restarts
  std::vector<std::int32_t> type;     // material index
  std::vector<double> radius;         // m
  std::vector<double> mass;           // kg
  std::vector<Vec3> position;         // m
  std::vector<Vec3> velocity;         // m/s
  std::vector<Vec3> angularVelocity;  // rad/s
  std::vector<Vec3> force;            // N, contact + body forces of the current step
  std::vector<Vec3> torque;           // N m
  /// N, set by the coupling (fluid forces), held over DEM substeps; with externalTorque (N m) sized
  /// only once enableExternalForces() was called (empty in DEM-only runs: 48 bytes per particle
  /// less, and the force loop reads nothing for them).
  std::vector<Vec3> externalForce;
  std::vector<Vec3> externalTorque;
  /// True iff externalForce and externalTorque are sized (one entry per particle, kept so by add and
  /// gather); the force loop adds them only then.
  bool hasExternalForces = false;
  /// False only while externalTorque is all zero (a coupling without fluid torque): the force loop
  /// then reads externalForce alone (24 bytes per particle and DEM step less). Whoever writes a
  /// non-zero external torque sets it (enableExternalForces sets it too); clearExternalTorques()
  /// resets it.
  bool hasExternalTorques = false;
  /// The particle's place in the order of the arrays: the Morton code of its cell at the last
  /// reordering (kNewParticleKey for particles added since). The arrays are kept sorted by
  /// (orderKey, id), a rule every rank applies to the particles it holds, so a contact's partners
  /// are summed in the same order on any number of ranks.
  std::vector<std::uint64_t> orderKey;
  static constexpr std::uint64_t kNewParticleKey = ~std::uint64_t{0};
  /// Under MPI: 1 for ghosts (copies of other ranks' particles within the contact reach, for the
  /// force loop only; their owner integrates them), 0 for the particles this rank owns. Empty on
  /// one rank (no ghosts).
  std::vector<std::uint8_t> ghost;
  bool isGhost(std::size_t i) const { return !ghost.empty() && ghost[i] != 0; }
  /// The particles this rank owns (all on one rank).
  std::size_t ownedCount() const;

  /// Identifies the particles and their order: a fresh value (process-wide counter, never 0)
  /// whenever add, gather or load change them; a copy of the set shares it. Whoever keeps
  /// per-particle data in the set's order can compare it instead of the id arrays (the coupler,
  /// every coupling step: 2 comparisons and a copy of 8 bytes per particle, on one thread, before).
  /// Code that edits `id` itself must call touchLayout().
  std::uint64_t layoutStamp = nextLayoutStamp();
  void touchLayout() { layoutStamp = nextLayoutStamp(); }
  static std::uint64_t nextLayoutStamp();

  /// Extra per-particle values that another subsystem keeps in the set's order (the coupling's
  /// drag coefficient, slip velocity, substep sums): named columns that travel with their
  /// particle. add() appends each column's fill value, gather() moves them like the arrays above
  /// (reordering, removal), load() sets them to their fill value. Registered with addColumn (one
  /// line per column); loops take the column's values.data(). Not part of save()/load(): whoever
  /// needs one across a restart writes it (the coupler does, with the ids).
  template <class T>
  struct Column {
    std::string name;
    T fill{};
    std::vector<T> values;  // one per particle
  };
  std::vector<Column<double>> doubleColumns;
  std::vector<Column<Vec3>> vec3Columns;
  /// The index in doubleColumns (vec3Columns) of the column `name`, created with every particle
  /// at `fill` if there is none (an existing one keeps its values and fill).
  std::size_t addColumn(const std::string& name, double fill);
  std::size_t addColumn(const std::string& name, const Vec3& fill);
  static constexpr std::size_t kNoColumn = static_cast<std::size_t>(-1);
  /// The index of the column `name`, or kNoColumn.
  std::size_t findDoubleColumn(const std::string& name) const;
  std::size_t findVec3Column(const std::string& name) const;

  std::size_t size() const { return id.size(); }

  /// Sizes externalForce and externalTorque (new entries zero) and sets hasExternalForces; whoever
  /// writes external forces calls it first. No-op if already enabled.
  void enableExternalForces();
  /// Sets every external torque to zero (once: no pass if already so) and hasExternalTorques false.
  void clearExternalTorques();

  /// Appends one particle; returns its index.
  std::size_t add(std::int64_t newId, std::int32_t materialType, double r, double density, const Vec3& x,
                  const Vec3& v = {}, const Vec3& omega = {});
  /// Moment of inertia of a solid sphere, I = 2/5 m r^2.
  double inertia(std::size_t i) const { return 0.4 * mass[i] * radius[i] * radius[i]; }

  /// Reorders all arrays, the columns included: new index k holds the particle that had index order[k].
  /// Particles whose old index is not in `order` are dropped (removal).
  void gather(const std::vector<std::uint32_t>& order);
  void reserve(std::size_t n);

  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);
};

}  // namespace gf::dem
