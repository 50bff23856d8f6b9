#include "dem/insertion/inserter.hpp"

#include <cmath>

namespace gf::dem {

const ContactTable*& InsertionCommon::table() {
  static const ContactTable* current = nullptr;
  return current;
}

InsertionCommon::InsertionCommon(Params& p) {
  material = table()->readMaterial(p, {"material", "-", "material name of the inserted particles"});
  density = p.documenting() ? 2500.0 : table()->materials()[material].density;
  size = readSizeDistribution(p);
  velocity = p.vec3({"velocity", "m/s", "initial velocity of inserted particles"}, {});
  const Key cg{"coarse_graining", "-",
               "coarse-graining factor alpha >= 1 (seed 003 eq. 3.34): each particle is a parcel standing for "
               "alpha^3 primary particles of diameter d / alpha (size gives the parcel diameter d); the drag uses the "
               "primary diameter, contacts the material as given (docs/coupling.md sec. 9); default: "
               "coupling.coarse_grain_factor. Insertions of the same material share one factor",
               Range::atLeast(1.0)};
  if (p.documenting() || p.has("coarse_graining")) coarseGraining = p.real(cg, 1.0);
  rng.setState(static_cast<std::uint64_t>(p.integer({"seed", "-", "random seed", Range::atLeast(0)}, 1)));
}

void OverlapGrid::add(const Vec3& x, double r) {
  cells_[key(static_cast<int>(std::floor(x.x / h_)), static_cast<int>(std::floor(x.y / h_)),
             static_cast<int>(std::floor(x.z / h_)))]
      .push_back({x, r});
}

bool OverlapGrid::overlaps(const Vec3& x, double r) const {
  const int ci = static_cast<int>(std::floor(x.x / h_)), cj = static_cast<int>(std::floor(x.y / h_)),
            ck = static_cast<int>(std::floor(x.z / h_));
  for (int i = ci - 1; i <= ci + 1; ++i)
    for (int j = cj - 1; j <= cj + 1; ++j)
      for (int k = ck - 1; k <= ck + 1; ++k) {
        auto it = cells_.find(key(i, j, k));
        if (it == cells_.end()) continue;
        for (const auto& [y, s] : it->second)
          if (normSquared(x - y) < (r + s) * (r + s)) return true;
      }
  return false;
}

}  // namespace gf::dem
