#include "core/domain.hpp"

#include <fmt/format.h>

#include <cmath>

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
  // Ranks per axis under mpirun: the word auto, or a list [px, py, pz] whose product is the rank
  // count (checked when the run starts, where the rank count is known).
  const Key layoutKey{"decomposition", "-",
                      "ranks per axis under MPI: auto (least halo surface) or [px, py, pz] with px*py*pz = ranks"};
  if (p.isSequence("decomposition")) {
    const std::vector<double> layout = p.reals(layoutKey, {0, 0, 0});
    if (layout.size() != 3) p.fail("decomposition", fmt::format("{} values", layout.size()), "auto or [px, py, pz]");
    for (int a = 0; a < 3; ++a) {
      if (!(layout[a] >= 1.0) || layout[a] != std::floor(layout[a]))
        p.fail("decomposition", fmt::format("{:g} ranks along {}", layout[a], "xyz"[a]),
               "auto or three whole numbers >= 1");
      d.decomposition[a] = static_cast<int>(layout[a]);
    }
  } else {
    p.choice(layoutKey, {"auto"}, "auto");  // (auto: the layout is chosen when the rank count is known)
  }
  return d;
}

}  // namespace gf
