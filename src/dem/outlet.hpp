#pragma once
// Deletion regions: particles whose centre enters the box are removed; their mass is counted.
#include <string>

#include "core/params.hpp"
#include "core/vec3.hpp"

namespace gf::dem {

struct Outlet {
  std::string name;
  Vec3 min, max;
  double removedMass = 0.0;  // kg, since the start of the run
  long long removedCount = 0;

  explicit Outlet(Params& p);
  bool contains(const Vec3& x) const {
    return x.x >= min.x && x.x <= max.x && x.y >= min.y && x.y <= max.y && x.z >= min.z && x.z <= max.z;
  }
};

}  // namespace gf::dem
