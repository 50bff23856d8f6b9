#pragma once
// The DEM half of the solver: particles, materials, walls, contacts, integration.
// Contract used by the application loop and the coupling:
//   System(root, domain, gravity)  reads the case sections it owns and inserts particles
//   step(dt)                       one DEM step (forces incl. particles().externalForce, then integrate)
//   checkHealth(step, time)        throws DivergenceError on NaN/Inf or a particle leaving the domain
//   save/load                      complete state for bit-identical restarts
#include <string>
#include <vector>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "core/serialize.hpp"
#include "core/timers.hpp"
#include "dem/particles.hpp"

namespace gf::dem {

struct Material {
  std::string name;
  double density = 2500.0;        // kg/m^3
  double youngsModulus = 1e7;     // Pa
  double poissonRatio = 0.3;      // -
  double restitution = 0.5;       // -
  double friction = 0.5;          // -
};

struct PlaneWall {
  Vec3 point;
  Vec3 normal;  // unit, pointing into the domain
};

class System {
 public:
  System(Params& root, const Domain& domain, const Vec3& gravity);

  void step(double dt);
  void checkHealth(long long step, double time) const;

  ParticleSet& particles() { return particles_; }
  const ParticleSet& particles() const { return particles_; }
  const std::vector<Material>& materials() const { return materials_; }
  /// Rayleigh time of the smallest/softest particle (s).
  double rayleighTime() const;
  PhaseTimers& timers() { return timers_; }

  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);

 private:
  void computeForces();
  Domain domain_;
  Vec3 gravity_;
  ParticleSet particles_;
  std::vector<Material> materials_;
  std::vector<PlaneWall> walls_;
  PhaseTimers timers_;
};

}  // namespace gf::dem
