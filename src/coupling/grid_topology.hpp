#pragma once
// The fluid grid as the coupling sees it: this rank's cell-centred fields plus what lies beyond
// each side of its box. Maps any integer cell index (also outside the grid) to a cell of the fields:
//   periodic direction (one rank along it) -> wrapped (modulo n);
//   wall side   -> folded back (mirror image about the wall: -1 -> 0, -2 -> 1, n -> n-1), then
//                  clamped; weight that a kernel puts outside a wall is thereby returned to the
//                  cells next to the wall and the particle volume is conserved;
//   shared side (a neighbour rank's box beyond it, periodic axes split among ranks included) ->
//                  the ghost cell itself, clamped to the ghost layers: deposits there are summed
//                  into the neighbour's cells (parallel::sumGhosts), samples read the neighbour's
//                  values (parallel::fillGhosts). A particle this rank owns lies within half a
//                  Verlet skin of the box, so its stencil stays within the ghost layers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "core/grid.hpp"
#include "parallel/decomposition.hpp"

namespace gf::coupling {

/// floor(x) as int without a libm call (x within int range).
inline int floorToInt(double x) {
  const int i = static_cast<int>(x);
  return x < i ? i - 1 : i;
}

struct GridTopology {
  CartesianGrid grid;
  /// Wrapped on this rank: periodic with one rank along the axis.
  std::array<bool, 3> periodic{false, false, false};
  /// [axis][0: lower side, 1: upper side]: a neighbour rank's cells lie beyond that side.
  std::array<std::array<bool, 2>, 3> shared{};
  Vec3 inverseSpacing{1.0, 1.0, 1.0};
  /// The ranks' layout where the grid is split among MPI ranks (nullptr: one rank, the whole grid).
  const parallel::Decomposition* decomposition = nullptr;

  GridTopology() = default;
  GridTopology(const CartesianGrid& g, const std::array<bool, 3>& p)
      : grid(g), periodic(p), inverseSpacing{1.0 / g.spacing.x, 1.0 / g.spacing.y, 1.0 / g.spacing.z} {}
  /// This rank's box `g` of a grid split as `d` says (d one rank: as the constructor above, with
  /// d's periodic axes). `d` must outlive the topology.
  GridTopology(const CartesianGrid& g, const parallel::Decomposition& d)
      : GridTopology(g, std::array<bool, 3>{false, false, false}) {
    for (int a = 0; a < 3; ++a) {
      periodic[a] = d.side(a, -1) == parallel::Side::Periodic;
      shared[a] = {d.side(a, -1) == parallel::Side::Shared, d.side(a, +1) == parallel::Side::Shared};
    }
    if (d.distributed()) decomposition = &d;
  }

  /// Whether a neighbour rank shares a side of this box (ghost cells then hold its cells).
  bool distributed() const { return decomposition != nullptr; }
  /// No wall below (dir 0) / above (dir 1) along the axis: the cells continue (wrapped or shared).
  bool open(int axis, int dir) const { return periodic[axis] || shared[axis][dir]; }

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
    const int g = grid.ghosts;
    if (i < 0) {
      if (shared[axis][0]) return std::max(i, -g);
      i = -1 - i;
    }
    if (i >= n) {
      if (shared[axis][1]) return std::min(i, n - 1 + g);
      i = 2 * n - 1 - i;
    }
    return i < 0 ? (shared[axis][0] ? std::max(i, -g) : 0) : (i >= n ? n - 1 : i);
  }
  /// Cell of a point (wrapped / folded like mapIndex; a ghost cell beyond a shared side).
  std::array<int, 3> cellOf(const Vec3& p) const {
    const auto c = rawCellOf(p);
    return {mapIndex(c[0], 0), mapIndex(c[1], 1), mapIndex(c[2], 2)};
  }
  /// Flat index of cell (i, j, k) (interior, or a ghost within the layers) in any cell-centred Field on this grid.
  std::size_t flat(int i, int j, int k) const {
    const int g = grid.ghosts;
    const std::size_t ex = static_cast<std::size_t>(grid.cells[0]) + 2 * static_cast<std::size_t>(g);
    const std::size_t ey = static_cast<std::size_t>(grid.cells[1]) + 2 * static_cast<std::size_t>(g);
    return (static_cast<std::size_t>(k + g) * ey + static_cast<std::size_t>(j + g)) * ex + static_cast<std::size_t>(i + g);
  }
  std::size_t flatMapped(int i, int j, int k) const { return flat(mapIndex(i, 0), mapIndex(j, 1), mapIndex(k, 2)); }
};

}  // namespace gf::coupling
