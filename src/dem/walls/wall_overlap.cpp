#include "dem/walls/wall_overlap.hpp"

#include <fmt/format.h>

#include <cmath>

namespace gf::dem {

void checkWallsDoNotOverlap(std::vector<Params>& wallEntries, const std::vector<WallPrimitive>& primitives,
                            const std::vector<std::string>& names, const std::vector<bool>& fixed) {
  constexpr double kParallel = 1.0 - 1e-12;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const WallPrimitive& p = primitives[i];
    if (p.kind != PrimitiveKind::Plane || !fixed[p.wall]) continue;
    for (std::size_t j = i + 1; j < primitives.size(); ++j) {
      const WallPrimitive& q = primitives[j];
      if (q.kind != PrimitiveKind::Plane || !fixed[q.wall] || q.wall == p.wall) continue;
      const double alignment = dot(p.b, q.b);
      const double offset = dot(q.a - p.a, p.b);  // position of q's plane along p's normal
      const double scale = 1e-9 * (1.0 + norm(p.a) + norm(q.a));
      Params& entry = wallEntries[q.wall];
      if (alignment > kParallel && std::abs(offset) <= scale)
        entry.fail("type", fmt::format("wall '{}' puts a plane where wall '{}' already has one (normal [{:g}, {:g}, {:g}])",
                                       names[q.wall], names[p.wall], q.b.x, q.b.y, q.b.z),
                   "walls that do not overlap (a particle would feel this surface twice)");
      if (alignment < -kParallel && offset <= scale)
        entry.fail("type", fmt::format("wall '{}' faces wall '{}' from {:g} m behind it", names[q.wall], names[p.wall], -offset),
                   "facing walls with room between them (they overlap)");
    }
  }
}

}  // namespace gf::dem
