#pragma once
// Particle-wall contact candidates: per particle, the wall primitives within r + skin, with
// their tangential/rolling history and the last force (for wall loads), rebuilt together with
// the particle neighbour list and carried over by (particle, primitive).
#include <cstdint>
#include <vector>

#include "core/serialize.hpp"
#include "dem/particles.hpp"
#include "dem/walls/wall_primitive.hpp"

namespace gf::dem {

class WallContactList {
 public:
  std::vector<std::uint32_t> rowStart;   // size n + 1
  std::vector<std::uint32_t> primitive;  // index into the primitives
  std::vector<Vec3> tangentialHistory;
  std::vector<Vec3> rollingHistory;      // EPSD only
  std::vector<Vec3> force;               // on the particle, last evaluation, N
  std::vector<Vec3> point;               // contact point, last evaluation, m
  std::vector<std::uint32_t> particle;   // particle (row) of each entry; derived from rowStart, not saved

  /// Sets `particle` of the entries of row i (from rowStart).
  void assignRowParticle(std::size_t i) {
    for (std::uint32_t k = rowStart[i]; k < rowStart[i + 1]; ++k) particle[k] = static_cast<std::uint32_t>(i);
  }

  void build(const ParticleSet& p, const std::vector<WallPrimitive>& primitives, double skin,
             const std::vector<std::int64_t>& previousIndex, bool withRollingHistory);
  std::size_t entries() const { return primitive.size(); }
  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);

 private:
  std::vector<std::vector<std::uint32_t>> scratch_;  // chunk buffers of build()
};

}  // namespace gf::dem
