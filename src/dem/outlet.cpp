#include "dem/outlet.hpp"

namespace gf::dem {

Outlet::Outlet(Params& p) {
  name = p.text({"name", "-", "outlet name (for monitors)"}, "outlet");
  min = p.vec3({"min", "m", "lower corner of the deletion box"});
  max = p.vec3({"max", "m", "upper corner of the deletion box"});
}

}  // namespace gf::dem
