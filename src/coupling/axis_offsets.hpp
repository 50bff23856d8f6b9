#pragma once
// Flat-index offsets of cell indices along one axis (mapIndex times the axis stride: walls fold,
// periodic axes wrap), tabulated for the indices a particle near the grid can reach, so that hot
// loops look them up instead of branching on the boundary kind. Used by the trilinear sampler and
// the divided void-fraction scheme's block path.
#include <cstddef>
#include <vector>

#include "coupling/grid_topology.hpp"

namespace gf::coupling {

template <class Offset>  // std::ptrdiff_t or std::size_t (mapIndex is never negative)
class AxisOffsetTable {
 public:
  static constexpr int kFirst = -2;  // first tabulated cell index; the last is cells + 2

  AxisOffsetTable() = default;
  AxisOffsetTable(const GridTopology& t, int axis, Offset stride) : axis_(axis), stride_(stride) {
    const int n = t.grid.cells[axis];
    for (int i = kFirst; i <= n + 2; ++i) offset_.push_back(static_cast<Offset>(t.mapIndex(i, axis)) * stride);
  }

  /// Offsets of cells `lower` and `lower + 1`; mapIndex itself outside the table.
  void pair(const GridTopology& t, int lower, Offset& lo, Offset& hi) const {
    const auto k = static_cast<std::size_t>(lower - kFirst);
    if (k < offset_.size() - 1) {  // (k wraps to a huge value below the table)
      lo = offset_[k];
      hi = offset_[k + 1];
    } else {
      lo = static_cast<Offset>(t.mapIndex(lower, axis_)) * stride_;
      hi = static_cast<Offset>(t.mapIndex(lower + 1, axis_)) * stride_;
    }
  }

 private:
  int axis_ = 0;
  Offset stride_ = 1;
  std::vector<Offset> offset_;
};

}  // namespace gf::coupling
