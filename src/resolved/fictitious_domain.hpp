#pragma once
// Resolved CFD-DEM by the fictitious-domain method of cfdemSolverIB (seed 000 lines 301-631): bodies
// larger than the fluid cells, the fluid solved on the whole domain and the bodies' rigid motion
// imposed on it as a body force (docs/resolved.md).
//
// One fluid (coupling) step, FictitiousDomain::fluidStep (seed lines 471-510):
//   1. momentum predictor on the whole domain (fluid::Solver, u-hat); fixed bodies with the implicit
//      forcing (resolved.forcing, the default) are held by a penalty term inside it (forcing.hpp);
//   2. explicit forcing (particles; fixed bodies with forcing: explicit): in the faces each body
//      covers, u-tilde = u-hat + phi (U + omega x r - u-hat) (forcing.hpp), the force of that forcing
//      summed per body (fluid::Solver::setPredictorHook);
//   3. pressure projection (fluid::Solver);
//   4. hydrodynamic force and torque of each body: the forcing's, the rigid-body correction for the
//      fluid inside it, and the buoyancy (the fluid of a resolved case carries no gravity: it solves
//      for the pressure less the hydrostatic part) (seed eqs. 2.15-2.25, lines 411-464);
//   5. the DEM particles' external force and torque set to theirs: the DEM sub-steps then integrate
//      their motion and collisions (time.coupling_interval DEM steps per fluid step).
// Bodies: every DEM particle is a free resolved sphere; `resolved.bodies` adds fixed spheres, 2D
// cylinders (axis z) and closed STL meshes (mesh_body.hpp), optionally rotating at a prescribed
// angular velocity.
//
// Under MPI each rank forces the cells and faces of its own box and the fixed bodies' sums are added
// over the ranks (parallel::sumOverRanks); the app refuses resolved particles on several ranks for now
// (docs/resolved.md).
#include <cstdint>
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "core/serialize.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/particles.hpp"
#include "dem/walls/wall_primitive.hpp"
#include "fluid/solver.hpp"
#include "resolved/forcing.hpp"
#include "resolved/lubrication.hpp"

namespace gf::resolved {

/// Hydrodynamic load on one body over the last fluid step.
struct BodyLoad {
  Vec3 force;   // N, total hydrodynamic force (forcing + rigid-body correction + buoyancy)
  Vec3 torque;  // N m, about the body's centre
};

/// A body of `resolved.bodies`: fixed in place, optionally rotating.
struct FixedBody {
  Body body;
  double referenceArea = 0.0;  // m^2, A of the force coefficients (resolved.bodies[].reference_area)
  int material = -1;           // index in the DEM's contact table (sphere, cylinder); -1: no contacts
  std::size_t historyColumn = dem::ParticleSet::kNoColumn;  // the particles' tangential history with it
  std::size_t rollingColumn = dem::ParticleSet::kNoColumn;  // and rolling history (EPSD)
  Vec3 fluidMomentum, fluidAngularMomentum;  // the last step's sum phi u V (rigid-body correction)
  BodyLoad load;
};

class FictitiousDomain {
 public:
  /// Reads section `resolved`, checks the resolution (warning below resolved.warn_cells_per_diameter,
  /// error below resolved.min_cells_per_diameter) and that no particle overlaps a fixed body,
  /// installs the forcing hook on the fluid solver. Throws CaseError. In documentation mode it
  /// only declares the keys. `contacts`: the DEM's contact table, for the contacts of the particles
  /// with the fixed spheres and cylinders (none if null).
  FictitiousDomain(Params& root, fluid::Solver& fluid, dem::ParticleSet& particles, const Domain& domain,
                   const Vec3& gravity, const dem::ContactTable* contacts = nullptr);

  /// One fluid step with the forcing, then every body's load; the particles' external force and
  /// torque become theirs (held over the DEM sub-steps).
  void fluidStep(fluid::Solver& fluid, dem::ParticleSet& particles, double dt);

  /// Before each DEM sub-step of length dt, in place of the last sub-step's in the particles' external
  /// force and torque: the lubrication correction (resolved.lubrication; nothing when off) at their
  /// current gaps and velocities, against each other, the fixed spheres and the DEM's walls (their
  /// current primitives, taken at rest); and the contact forces of the DEM's contact law with the
  /// fixed spheres and cylinders. (Per sub-step: the gap closes by a large part of the range within
  /// one fluid step, and the correction grows as 1 / h; a contact lasts a few dozen sub-steps.)
  void beforeDemStep(dem::ParticleSet& particles, double dt, const std::vector<dem::WallPrimitive>& walls);

  const std::vector<FixedBody>& fixedBodies() const { return fixed_; }
  const LubricationSettings& lubrication() const { return lubrication_; }
  /// Load of the particle with this id over the last step (zero if there is none on this rank).
  BodyLoad particleLoad(const dem::ParticleSet& particles, std::int64_t id) const;
  double fluidDensity() const { return rho_; }
  /// Extent of the domain along z (the length of a 2D cylinder), m.
  double depth() const { return depth_; }

  void save(BinaryWriter& out, const dem::ParticleSet& particles) const;
  void load(BinaryReader& in, dem::ParticleSet& particles);

 private:
  void impose(Field (&u)[3], double dt, double gamma0);
  /// The lubrication forces (lubrication.hpp) on the owned particles `owned` (pairs, fixed spheres,
  /// walls), added to `force` (one per particle of the set).
  void lubricationForces(const dem::ParticleSet& particles, const std::vector<std::size_t>& owned, double dt,
                         const std::vector<dem::WallPrimitive>& walls, std::vector<Vec3>& force) const;
  /// The contact forces and torques of the owned particles with the fixed spheres and cylinders (the
  /// DEM's contact law, the body as a wall of its material moving with its rigid velocity), added to
  /// `force` and `torque`; updates the tangential histories.
  void bodyContactForces(dem::ParticleSet& particles, const std::vector<std::size_t>& owned, double dt,
                         std::vector<Vec3>& force, std::vector<Vec3>& torque);
  /// The particle columns of the sub-step forces and the contact histories (when needed).
  void addSubstepColumns(dem::ParticleSet& particles);
  /// Implicit forcing: K and the K-weighted body velocity of the covered cells (fluid coupling fields).
  void setPenalty(fluid::Solver& fluid, double diagonal);
  /// The momentum sums of every body for the current velocity (after the projection).
  void sumFluidMomentum(const fluid::Solver& fluid);
  Body particleBody(const dem::ParticleSet& p, std::size_t i) const;
  /// The body the forcing covers: its radius larger by resolved.radius_offset cells.
  Body forcingBody(Body b) const {
    b.radius += radiusOffset_;
    return b;
  }

  FaceBox box_;
  double rho_ = 1.0;
  double radiusOffsetCells_ = 0.0, radiusOffset_ = 0.0;  // resolved.radius_offset in cells, in m
  double depth_ = 1.0;
  Vec3 domainSize_;  // m (the minimum image along periodic axes)
  double viscosity_ = 0.0;
  LubricationSettings lubrication_;
  Vec3 gravity_;
  bool distributed_ = false;
  bool implicit_ = true;                  // resolved.forcing
  bool particleImplicit_ = false;         // resolved.particle_forcing
  bool viscousWarned_ = false;            // the explicit forcing's nu dt / h^2 warning, given once
  std::vector<std::size_t> penaltyCells_;  // cells with K > 0 (implicit forcing)
  bool penaltyCellsKnown_ = false;         // penaltyCells_ lists every cell with K > 0
  std::vector<FixedBody> fixed_;
  // Per step (set by fluidStep before the fluid step, read by the hook).
  std::vector<Body> particleBodies_;
  std::vector<FaceSums> forcingSums_;  // fixed bodies, then particles
  const dem::ParticleSet* stepParticles_ = nullptr;
  // Particle columns (dem::ParticleSet::addColumn): the fluid momentum inside each particle at the
  // end of the last step and whether it is set (a new particle has no previous value).
  std::size_t momentumColumn_ = dem::ParticleSet::kNoColumn;
  std::size_t angularColumn_ = dem::ParticleSet::kNoColumn;
  std::size_t knownColumn_ = dem::ParticleSet::kNoColumn;
  // The sub-step forces and torques in each particle's external force and torque (beforeDemStep),
  // zeroed by fluidStep.
  std::size_t substepForceColumn_ = dem::ParticleSet::kNoColumn;
  std::size_t substepTorqueColumn_ = dem::ParticleSet::kNoColumn;
  const dem::ContactTable* contacts_ = nullptr;
  bool bodyContacts_ = false;  // a fixed body with contacts
  bool fixedKnown_ = false;
};

/// Smallest number of cells across a diameter of a body of radius r on a grid of spacing h
/// (a cylinder along z: x and y only).
inline double cellsPerDiameter(double radius, const Vec3& h, bool cylinder) {
  const double hmax = cylinder ? std::max(h.x, h.y) : std::max({h.x, h.y, h.z});
  return 2.0 * radius / hmax;
}

}  // namespace gf::resolved
