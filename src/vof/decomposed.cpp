// The phase-fraction transport on a rank's box of a decomposed grid (vof/vof.hpp): the sides of the
// box and its ghost fill through parallel::fillGhosts.
#include "parallel/decomposition.hpp"
#include "parallel/halo.hpp"
#include "vof/vof.hpp"

namespace gf::vof {

Sides boxSides(const parallel::Decomposition& d) {
  Sides s;
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const parallel::Side t = d.side(a, side == 0 ? -1 : 1);
      s.side[static_cast<std::size_t>(2 * a + side)] =
          t == parallel::Side::Shared ? SideType::Shared : (t == parallel::Side::Periodic ? SideType::Periodic : SideType::Wall);
    }
  return s;
}

GhostFill decomposedFill(const parallel::Decomposition& d) { return decomposedFill(d, boxSides(d)); }

GhostFill decomposedFill(const parallel::Decomposition& d, const Sides& sides) {
  const parallel::Decomposition* dp = &d;
  return [dp, sides](const std::vector<Field*>& fields) {
    parallel::fillGhosts(fields, *dp);  // across the cuts, periodic wrap between ranks included
    for (Field* f : fields) fillCellGhosts(*f, sides);
  };
}

}  // namespace gf::vof
