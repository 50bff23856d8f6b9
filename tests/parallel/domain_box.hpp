#pragma once
// The domain [0, max] with the given periodic axes: the box the layout tests split.
#include <array>

#include "core/domain.hpp"

namespace gf::parallel::testing {

inline Domain box(Vec3 max, std::array<bool, 3> periodic = {false, false, false}) {
  Domain d;
  d.min = {0, 0, 0};
  d.max = max;
  d.periodic = periodic;
  return d;
}

}  // namespace gf::parallel::testing
