#include "dem/wall_contact_list.hpp"

#include "core/parallel.hpp"

namespace gf::dem {

void WallContactList::build(const ParticleSet& p, const std::vector<WallPrimitive>& primitives, double skin,
                            const std::vector<std::int64_t>& previousIndex, bool withRollingHistory) {
  const std::size_t n = p.size();
  const std::size_t np = primitives.size();
  auto near = [&](std::size_t i, std::size_t w) {
    const WallDistance d = distanceToPrimitive(primitives[w], p.position[i]);
    return d.distance < p.radius[i] + skin;
  };
  std::vector<std::uint32_t> count(n + 1, 0);
  parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t i) {
    std::uint32_t k = 0;
    for (std::size_t w = 0; w < np; ++w) k += near(i, w);
    count[i + 1] = k;
  });
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  std::vector<std::uint32_t> oldStart = std::move(rowStart);
  std::vector<std::uint32_t> oldPrimitive = std::move(primitive);
  std::vector<Vec3> oldTangential = std::move(tangentialHistory);
  std::vector<Vec3> oldRolling = std::move(rollingHistory);
  rowStart = std::move(count);
  const std::size_t m = rowStart[n];
  primitive.assign(m, 0);
  tangentialHistory.assign(m, Vec3{});
  rollingHistory.assign(withRollingHistory ? m : 0, Vec3{});
  force.assign(m, Vec3{});
  point.assign(m, Vec3{});
  const bool carryRolling = withRollingHistory && oldRolling.size() == oldPrimitive.size();
  const std::int64_t oldRows = oldStart.empty() ? 0 : static_cast<std::int64_t>(oldStart.size()) - 1;
  parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t i) {
    std::uint32_t k = rowStart[i];
    const std::int64_t oi = i < static_cast<std::int64_t>(previousIndex.size()) ? previousIndex[i] : -1;
    for (std::size_t w = 0; w < np; ++w) {
      if (!near(i, w)) continue;
      primitive[k] = static_cast<std::uint32_t>(w);
      if (oi >= 0 && oi < oldRows)
        for (std::uint32_t q = oldStart[oi]; q < oldStart[oi + 1]; ++q)
          if (oldPrimitive[q] == w) {
            tangentialHistory[k] = oldTangential[q];
            if (carryRolling) rollingHistory[k] = oldRolling[q];
            break;
          }
      ++k;
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
  if (tangentialHistory.size() != primitive.size() || force.size() != primitive.size())
    throw CheckpointError("checkpoint is corrupt: DEM wall contact arrays do not match");
}

}  // namespace gf::dem
