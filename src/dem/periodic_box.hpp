#pragma once
// Minimum-image convention for periodic directions of the domain.
#include <cmath>

#include "core/domain.hpp"

namespace gf::dem {

struct PeriodicBox {
  bool periodic[3] = {false, false, false};
  bool anyPeriodic = false;
  double length[3] = {0.0, 0.0, 0.0};
  double lower[3] = {0.0, 0.0, 0.0};
  double half[3] = {0.0, 0.0, 0.0};  // length / 2

  PeriodicBox() = default;
  explicit PeriodicBox(const Domain& d) {
    for (int a = 0; a < 3; ++a) {
      periodic[a] = d.periodic[a];
      length[a] = d.max[a] - d.min[a];
      lower[a] = d.min[a];
      half[a] = 0.5 * length[a];
    }
    anyPeriodic = periodic[0] || periodic[1] || periodic[2];
  }
  /// Shortest image of a separation vector of two positions inside the box (|d| < length, as
  /// wrap() keeps them): one compare per axis instead of a division and a rounding call.
  Vec3 minimumImage(Vec3 d) const {
    if (!anyPeriodic) return d;
    for (int a = 0; a < 3; ++a)
      if (periodic[a]) {
        if (d[a] > half[a]) d[a] -= length[a];
        else if (d[a] < -half[a]) d[a] += length[a];
      }
    return d;
  }
  /// Maps a position back into the box in periodic directions.
  Vec3 wrap(Vec3 x) const {
    if (!anyPeriodic) return x;
    for (int a = 0; a < 3; ++a)
      if (periodic[a]) {
        if (x[a] < lower[a]) x[a] += length[a];
        else if (x[a] >= lower[a] + length[a]) x[a] -= length[a];
      }
    return x;
  }
};

}  // namespace gf::dem
