#pragma once
// The fluid grid as the coupling sees it: cell-centred fields plus which directions are periodic.
// Maps any integer cell index (also outside the grid) to an interior cell:
//   periodic direction -> wrapped (modulo n);
//   wall direction     -> folded back (mirror image about the wall: -1 -> 0, -2 -> 1, n -> n-1),
//                         then clamped; weight that a kernel puts outside a wall is thereby returned
//                         to the cells next to the wall and the particle volume is conserved.
#include <array>
#include <cmath>
#include <cstddef>

#include "core/grid.hpp"

namespace gf::coupling {

/// floor(x) as int without a libm call (x within int range).
inline int floorToInt(double x) {
  const int i = static_cast<int>(x);
  return x < i ? i - 1 : i;
}

struct GridTopology {
  CartesianGrid grid;
  std::array<bool, 3> periodic{false, false, false};
  Vec3 inverseSpacing{1.0, 1.0, 1.0};

  GridTopology() = default;
  GridTopology(const CartesianGrid& g, const std::array<bool, 3>& p)
      : grid(g), periodic(p), inverseSpacing{1.0 / g.spacing.x, 1.0 / g.spacing.y, 1.0 / g.spacing.z} {}

  /// Unwrapped cell index of a point (may lie outside [0, n)).
  std::array<int, 3> rawCellOf(const Vec3& p) const {
    return {floorToInt((p.x - grid.origin.x) * inverseSpacing.x), floorToInt((p.y - grid.origin.y) * inverseSpacing.y),
            floorToInt((p.z - grid.origin.z) * inverseSpacing.z)};
  }

  int mapIndex(int i, int axis) const {
    const int n = grid.cells[axis];
    if (periodic[axis]) {
      if (i >= 0 && i < n) return i;
      return ((i % n) + n) % n;
    }
    if (i < 0) i = -1 - i;
    if (i >= n) i = 2 * n - 1 - i;
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
  }
  /// Interior cell of a point (wrapped / folded like mapIndex).
  std::array<int, 3> cellOf(const Vec3& p) const {
    const auto c = rawCellOf(p);
    return {mapIndex(c[0], 0), mapIndex(c[1], 1), mapIndex(c[2], 2)};
  }
  /// Flat index of interior cell (i, j, k) in any cell-centred Field on this grid.
  std::size_t flat(int i, int j, int k) const {
    const int g = grid.ghosts;
    const std::size_t ex = static_cast<std::size_t>(grid.cells[0]) + 2 * static_cast<std::size_t>(g);
    const std::size_t ey = static_cast<std::size_t>(grid.cells[1]) + 2 * static_cast<std::size_t>(g);
    return (static_cast<std::size_t>(k + g) * ey + static_cast<std::size_t>(j + g)) * ex + static_cast<std::size_t>(i + g);
  }
  std::size_t flatMapped(int i, int j, int k) const { return flat(mapIndex(i, 0), mapIndex(j, 1), mapIndex(k, 2)); }
};

}  // namespace gf::coupling
