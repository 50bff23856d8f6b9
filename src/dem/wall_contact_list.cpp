#include "dem/wall_contact_list.hpp"

#include "dem/neighbour_list.hpp"

namespace gf::dem {

void WallContactList::build(const ParticleSet& p, const std::vector<WallPrimitive>& primitives, double skin,
                            const std::vector<std::int64_t>& previousIndex, bool withRollingHistory) {
  const std::size_t n = p.size();
  const std::uint32_t np = static_cast<std::uint32_t>(primitives.size());
  std::vector<std::uint32_t> oldStart = std::move(rowStart);
  std::vector<std::uint32_t> oldPrimitive = std::move(primitive);
  std::vector<Vec3> oldTangential = std::move(tangentialHistory);
  std::vector<Vec3> oldRolling = std::move(rollingHistory);
  const bool carryRolling = withRollingHistory && oldRolling.size() == oldPrimitive.size();
  const std::int64_t oldRows = oldStart.empty() ? 0 : static_cast<std::int64_t>(oldStart.size()) - 1;
  buildCompressedRows(
      n, scratch_, rowStart, primitive,
      [&](std::size_t i, std::vector<std::uint32_t>& out) {
        const Vec3 x = p.position[i];
        const double reach = p.radius[i] + skin;
        for (std::uint32_t w = 0; w < np; ++w) {
          const WallPrimitive& prim = primitives[w];
          // planes inline (the common box and distributor walls), the same value as distanceToPrimitive
          const double d = prim.kind == PrimitiveKind::Plane ? dot(x - prim.a, prim.b) : distanceToPrimitive(prim, x).distance;
          if (d < reach) out.push_back(w);
        }
      },
      [&](std::size_t m) {
        tangentialHistory.assign(m, Vec3{});
        rollingHistory.assign(withRollingHistory ? m : 0, Vec3{});
        force.assign(m, Vec3{});
        point.assign(m, Vec3{});
        particle.resize(m);
      },
      [&](std::size_t i) {  // history carried over by (particle, primitive)
        assignRowParticle(i);
        const std::int64_t oi = i < previousIndex.size() ? previousIndex[i] : -1;
        if (oi < 0 || oi >= oldRows) return;
        for (std::uint32_t k = rowStart[i]; k < rowStart[i + 1]; ++k)
          for (std::uint32_t q = oldStart[oi]; q < oldStart[oi + 1]; ++q)
            if (oldPrimitive[q] == primitive[k]) {
              tangentialHistory[k] = oldTangential[q];
              if (carryRolling) rollingHistory[k] = oldRolling[q];
              break;
            }
      });
}

void WallContactList::save(BinaryWriter& out) const {
  out.putVector(rowStart);
  out.putVector(primitive);
  out.putVector(tangentialHistory);
  out.putVector(rollingHistory);
  out.putVector(force);
  out.putVector(point);
}

void WallContactList::load(BinaryReader& in) {
  rowStart = in.getVector<std::uint32_t>();
  primitive = in.getVector<std::uint32_t>();
  tangentialHistory = in.getVector<Vec3>();
  rollingHistory = in.getVector<Vec3>();
  force = in.getVector<Vec3>();
  point = in.getVector<Vec3>();
  if (tangentialHistory.size() != primitive.size() || force.size() != primitive.size() ||
      (!rowStart.empty() && rowStart.back() != primitive.size()))
    throw CheckpointError("checkpoint is corrupt: DEM wall contact arrays do not match");
  particle.resize(primitive.size());
  for (std::size_t i = 0; i + 1 < rowStart.size(); ++i) assignRowParticle(i);
}

}  // namespace gf::dem
