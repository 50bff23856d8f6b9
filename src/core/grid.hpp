#pragma once
// Uniform Cartesian grid and flat fields with ghost layers.
//
// Layout: x fastest, then y, then z; ghost layers on every side. A field is one flat
// std::vector<double>, so a later split of the domain across MPI ranks (each rank owns a box of
// cells plus ghosts) and a GPU port (one device array) change no numerics.
//
// Staggering (MAC grid): cell-centred fields have n cells per direction; a face field for the
// velocity component along axis a has n+1 faces along a (face f sits at origin + f*spacing[a]).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/vec3.hpp"

namespace gf {

enum class Staggering { Cell, FaceX, FaceY, FaceZ };

struct CartesianGrid {
  Vec3 origin;                      // lower corner of the interior, m
  Vec3 spacing{1.0, 1.0, 1.0};      // cell size per direction, m
  std::array<int, 3> cells{1, 1, 1};  // interior cells per direction
  int ghosts = 2;                   // ghost layers on every side

  double cellVolume() const { return spacing.x * spacing.y * spacing.z; }
  std::size_t interiorCellCount() const {
    return static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) * static_cast<std::size_t>(cells[2]);
  }
  Vec3 upper() const {
    return {origin.x + cells[0] * spacing.x, origin.y + cells[1] * spacing.y, origin.z + cells[2] * spacing.z};
  }
  Vec3 cellCentre(int i, int j, int k) const {
    return {origin.x + (i + 0.5) * spacing.x, origin.y + (j + 0.5) * spacing.y, origin.z + (k + 0.5) * spacing.z};
  }
  /// Index of the cell containing point p (may be outside [0, n) for points outside).
  std::array<int, 3> cellOf(const Vec3& p) const {
    return {static_cast<int>(std::floor((p.x - origin.x) / spacing.x)),
            static_cast<int>(std::floor((p.y - origin.y) / spacing.y)),
            static_cast<int>(std::floor((p.z - origin.z) / spacing.z))};
  }
  bool isInterior(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < cells[0] && j < cells[1] && k < cells[2];
  }
};

/// A scalar on the grid (cell centres or one family of faces), ghosts included, flat storage.
class Field {
 public:
  Field() = default;
  explicit Field(const CartesianGrid& grid, Staggering staggering = Staggering::Cell, double initial = 0.0)
      : grid_(grid), staggering_(staggering) {
    for (int a = 0; a < 3; ++a) {
      const int faces = (static_cast<int>(staggering) == a + 1) ? 1 : 0;
      points_[a] = grid.cells[a] + faces;
      extent_[a] = points_[a] + 2 * grid.ghosts;
    }
    data_.assign(static_cast<std::size_t>(extent_[0]) * extent_[1] * extent_[2], initial);
  }

  /// Flat index of (i, j, k); interior points are 0..points-1, ghosts are negative or >= points.
  std::size_t index(int i, int j, int k) const {
    const int g = grid_.ghosts;
    return (static_cast<std::size_t>(k + g) * extent_[1] + static_cast<std::size_t>(j + g)) * extent_[0] +
           static_cast<std::size_t>(i + g);
  }
  double& operator()(int i, int j, int k) { return data_[index(i, j, k)]; }
  double operator()(int i, int j, int k) const { return data_[index(i, j, k)]; }
  /// Distance in the flat array between neighbours along axis a.
  std::ptrdiff_t stride(int axis) const {
    return axis == 0 ? 1 : (axis == 1 ? extent_[0] : static_cast<std::ptrdiff_t>(extent_[0]) * extent_[1]);
  }

  void fill(double v) { std::fill(data_.begin(), data_.end(), v); }
  std::vector<double>& data() { return data_; }
  const std::vector<double>& data() const { return data_; }
  const CartesianGrid& grid() const { return grid_; }
  Staggering staggering() const { return staggering_; }
  /// Interior points per direction (cells, or cells+1 along the staggered axis).
  const std::array<int, 3>& points() const { return points_; }
  const std::array<int, 3>& extent() const { return extent_; }

 private:
  CartesianGrid grid_;
  Staggering staggering_ = Staggering::Cell;
  std::array<int, 3> points_{0, 0, 0};
  std::array<int, 3> extent_{0, 0, 0};
  std::vector<double> data_;
};

}  // namespace gf
