#pragma once
// Consistency check of the wall set: two fixed walls must not put a plane at the same place
// (a particle would feel that surface twice, e.g. a 'box' plus a 'plane' floor), and two facing
// planes must leave room between them.
#include <string>
#include <vector>

#include "core/params.hpp"
#include "dem/walls/wall_primitive.hpp"

namespace gf::dem {

/// Throws CaseError (at the later wall's entry) when two fixed walls overlap as described above.
/// `fixed[w]` is false for walls that move or disappear, which are not checked.
void checkWallsDoNotOverlap(std::vector<Params>& wallEntries, const std::vector<WallPrimitive>& primitives,
                            const std::vector<std::string>& names, const std::vector<bool>& fixed);

}  // namespace gf::dem
