#pragma once
// The simulation box shared by DEM and fluid: an axis-aligned box with optional periodicity.
#include <array>

#include "core/params.hpp"
#include "core/vec3.hpp"

namespace gf {

struct Domain {
  Vec3 min;
  Vec3 max;
  std::array<bool, 3> periodic{false, false, false};
  /// Ranks per axis under MPI (domain.decomposition); {0, 0, 0} = auto (least halo surface).
  std::array<int, 3> decomposition{0, 0, 0};

  Vec3 size() const { return max - min; }
  bool contains(const Vec3& p) const {
    return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y && p.z >= min.z && p.z <= max.z;
  }
  /// Reads section 'domain' of a case (min, max, periodic).
  static Domain read(Params& root);
};

}  // namespace gf
