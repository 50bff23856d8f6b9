#include "coupling/interpolation.hpp"

#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

/// d(field)/dx_axis at interior cell (i, j, k): central where both neighbours exist (or wrap),
/// one-sided at walls.
double derivative(const GridTopology& t, const Field& f, int i, int j, int k, int axis) {
  int idx[3] = {i, j, k};
  const int n = t.grid.cells[axis];
  const double h = t.grid.spacing[axis];
  int lo[3] = {i, j, k}, hi[3] = {i, j, k};
  double span = 2.0 * h;
  if (t.periodic[axis] || (idx[axis] > 0 && idx[axis] < n - 1)) {
    lo[axis] = t.mapIndex(idx[axis] - 1, axis);
    hi[axis] = t.mapIndex(idx[axis] + 1, axis);
  } else {
    lo[axis] = std::max(idx[axis] - 1, 0);
    hi[axis] = std::min(idx[axis] + 1, n - 1);
    span = (hi[axis] - lo[axis]) * h;
    if (span == 0.0) return 0.0;
  }
  return (f(hi[0], hi[1], hi[2]) - f(lo[0], lo[1], lo[2])) / span;
}

template <class Body>
void forInteriorCells(const GridTopology& t, Body&& body) {
  const auto& n = t.grid.cells;
  forEachIndex(static_cast<std::int64_t>(n[2]) * n[1], n[0], [&](std::int64_t kj) {
    const int k = static_cast<int>(kj / n[1]);
    const int j = static_cast<int>(kj % n[1]);
    for (int i = 0; i < n[0]; ++i) body(i, j, k);
  });
}

}  // namespace

void computeVorticity(const GridTopology& t, const Field* const (&u)[3], Field (&curl)[3]) {
  forInteriorCells(t, [&](int i, int j, int k) {
    curl[0](i, j, k) = derivative(t, *u[2], i, j, k, 1) - derivative(t, *u[1], i, j, k, 2);
    curl[1](i, j, k) = derivative(t, *u[0], i, j, k, 2) - derivative(t, *u[2], i, j, k, 0);
    curl[2](i, j, k) = derivative(t, *u[1], i, j, k, 0) - derivative(t, *u[0], i, j, k, 1);
  });
}

void computeViscousStressDivergence(const GridTopology& t, const Field* const (&u)[3], double viscosity,
                                    Field (&divTau)[3]) {
  double h2[3];
  for (int a = 0; a < 3; ++a) h2[a] = t.grid.spacing[a] * t.grid.spacing[a];
  forInteriorCells(t, [&](int i, int j, int k) {
    const int idx[3] = {i, j, k};
    int lo[3], hi[3];  // neighbour cell along each axis minus this cell (wrapped, or clamped at walls)
    for (int a = 0; a < 3; ++a) {
      lo[a] = (t.periodic[a] ? t.mapIndex(idx[a] - 1, a) : std::max(idx[a] - 1, 0)) - idx[a];
      hi[a] = (t.periodic[a] ? t.mapIndex(idx[a] + 1, a) : std::min(idx[a] + 1, t.grid.cells[a] - 1)) - idx[a];
    }
    for (int c = 0; c < 3; ++c) {
      const Field& f = *u[c];
      const double* d = f.data().data() + f.index(i, j, k);
      const double centre = d[0];
      double lap = 0.0;
      for (int a = 0; a < 3; ++a) {
        const std::ptrdiff_t st = f.stride(a);
        lap += (d[hi[a] * st] - 2.0 * centre + d[lo[a] * st]) / h2[a];
      }
      divTau[c](i, j, k) = viscosity * lap;
    }
  });
}

}  // namespace gf::coupling
