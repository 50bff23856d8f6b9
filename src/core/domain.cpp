#include "core/domain.hpp"

#include <fmt/format.h>

namespace gf {

Domain Domain::read(Params& root) {
  Params p = root.requiredSection({"domain", "-", "axis-aligned simulation box"});
  Domain d;
  d.min = p.vec3({"min", "m", "lower corner of the box"});
  d.max = p.vec3({"max", "m", "upper corner of the box"});
  for (int a = 0; a < 3; ++a) {
    if (!p.documenting() && !(d.max[a] > d.min[a]))
      p.fail("max", fmt::format("max[{}] = {:g} <= min[{}] = {:g}", a, d.max[a], a, d.min[a]),
             "every component of max greater than min");
  }
  const std::vector<double> periodic =
      p.reals({"periodic", "-", "periodicity flags [x, y, z]: 1 = periodic, 0 = bounded", Range::between(0, 1)},
              {0, 0, 0});
  if (periodic.size() != 3) p.fail("periodic", fmt::format("{} values", periodic.size()), "3 flags [x, y, z]");
  for (int a = 0; a < 3; ++a) d.periodic[a] = periodic[a] != 0.0;
  return d;
}

}  // namespace gf
