#include "coupling/interpolation.hpp"

#include "coupling/loops.hpp"


namespace gf::coupling {
namespace {

/// d(field)/dx_axis at interior cell (i, j, k): central where both neighbours exist (inside, wrapped,
/// or a neighbour rank's ghost cell), one-sided at walls.
double derivative(const GridTopology& t, const Field& f, int i, int j, int k, int axis) {
  int idx[3] = {i, j, k};
  const int n = t.grid.cells[axis];
  const double h = t.grid.spacing[axis];
  int lo[3] = {i, j, k}, hi[3] = {i, j, k};
  const bool below = t.open(axis, 0) || idx[axis] > 0, above = t.open(axis, 1) || idx[axis] < n - 1;
  if (below) lo[axis] = t.mapIndex(idx[axis] - 1, axis);
  if (above) hi[axis] = t.mapIndex(idx[axis] + 1, axis);
  const double span = ((below ? 1 : 0) + (above ? 1 : 0)) * h;
  if (span == 0.0) return 0.0;
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

namespace {

GF_VECTOR_CLONES
void viscousStressDivergenceRow(const double* const (&u)[3], double* const (&out)[3], std::size_t first, int cells,
                                const std::ptrdiff_t (&lo)[3], const std::ptrdiff_t (&hi)[3], bool wallLowX,
                                bool wallHighX, const double (&h2)[3], double viscosity) {
  using Double4 = double __attribute__((vector_size(32)));  // components x, y, z (lane 3 unused)
  for (int i = 0; i < cells; ++i) {
    const std::size_t q = first + i;
    std::ptrdiff_t l[3] = {lo[0], lo[1], lo[2]}, h[3] = {hi[0], hi[1], hi[2]};
    if (wallLowX && i == 0) l[0] = 0;               // wall: the neighbour is the cell itself
    if (wallHighX && i == cells - 1) h[0] = 0;
    const Double4 centre{u[0][q], u[1][q], u[2][q], 0.0};
    Double4 lap{};
    for (int a = 0; a < 3; ++a) {
      const Double4 up{u[0][q + h[a]], u[1][q + h[a]], u[2][q + h[a]], 0.0};
      const Double4 down{u[0][q + l[a]], u[1][q + l[a]], u[2][q + l[a]], 0.0};
      lap += (up - 2.0 * centre + down) / h2[a];
    }
    const Double4 result = viscosity * lap;
    out[0][q] = result[0], out[1][q] = result[1], out[2][q] = result[2];
  }
}

}  // namespace

void computeViscousStressDivergence(const GridTopology& t, const Field* const (&u)[3], double viscosity,
                                    Field (&divTau)[3]) {
  // Per cell and component: sum over the axes of (u_hi - 2 u_c + u_lo) / h_a^2, the neighbour along
  // an axis wrapped (periodic) or clamped to the cell itself (wall), times mu. Rows along x; the
  // three components side by side in one vector (divisions three at a time; the same operations
  // per component as one at a time).
  double h2[3];
  for (int a = 0; a < 3; ++a) h2[a] = t.grid.spacing[a] * t.grid.spacing[a];
  const auto& n = t.grid.cells;
  const double* in[3] = {u[0]->data().data(), u[1]->data().data(), u[2]->data().data()};
  double* out[3] = {divTau[0].data().data(), divTau[1].data().data(), divTau[2].data().data()};
  const Field& f = *u[0];  // all fields share the layout (cell-centred on the grid)
  forEachIndex(static_cast<std::int64_t>(n[2]) * n[1], n[0], [&](std::int64_t kj) {
    const int k = static_cast<int>(kj / n[1]);
    const int j = static_cast<int>(kj % n[1]);
    const int idx[3] = {0, j, k};
    std::ptrdiff_t lo[3], hi[3];  // flat offsets of the neighbours (y, z: of this row; x: interior cells)
    for (int a = 1; a < 3; ++a) {
      const int l = (t.open(a, 0) ? t.mapIndex(idx[a] - 1, a) : std::max(idx[a] - 1, 0)) - idx[a];
      const int h = (t.open(a, 1) ? t.mapIndex(idx[a] + 1, a) : std::min(idx[a] + 1, n[a] - 1)) - idx[a];
      lo[a] = l * f.stride(a);
      hi[a] = h * f.stride(a);
    }
    lo[0] = -1, hi[0] = 1;
    // x: at i = 0 and i = n - 1 the neighbour across the boundary (wrapped, a neighbour rank's
    // ghost cell, or the cell itself at a wall)
    const bool periodicX = t.periodic[0];
    const std::size_t first = f.index(0, j, k);
    if (n[0] == 1 || periodicX) {
      // few or wrapped cells along x: cell by cell
      for (int i = 0; i < n[0]; ++i) {
        std::ptrdiff_t l[3] = {(t.open(0, 0) ? t.mapIndex(i - 1, 0) : std::max(i - 1, 0)) - i, lo[1], lo[2]};
        std::ptrdiff_t h[3] = {(t.open(0, 1) ? t.mapIndex(i + 1, 0) : std::min(i + 1, n[0] - 1)) - i, hi[1], hi[2]};
        viscousStressDivergenceRow(in, out, first + i, 1, l, h, false, false, h2, viscosity);
      }
    } else {
      viscousStressDivergenceRow(in, out, first, n[0], lo, hi, !t.open(0, 0), !t.open(0, 1), h2, viscosity);
    }
  });
}


GF_VECTOR_CLONES
void sampleTrilinearBlock(const TrilinearSampler::Location* where, int count, const double* buffer,
                          double (*out)[13]) {
  static_assert(kTrilinearBlockChannels == 10, "channels 0-7 in one vector of 8, 8-9 in one of 2");
  constexpr int kC = kTrilinearBlockChannels;
  using Double8 = double __attribute__((vector_size(64)));
  using Double2 = double __attribute__((vector_size(16)));
  for (int q = 0; q < count; ++q) {
    const TrilinearSampler::Location& l = where[q];
    const double* base = buffer + l.flat * kC;
    const double* frac = l.frac;
    Double8 low{};  // channels 0-7
    Double2 high{};  // channels 8-9
    // the corners, weights and order of sumTrilinearCorners
    for (int dk = 0; dk < 2; ++dk)
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          const double wm =
              (di ? frac[0] : 1.0 - frac[0]) * (dj ? frac[1] : 1.0 - frac[1]) * (dk ? frac[2] : 1.0 - frac[2]);
          const double* v = base + (di * l.step[0] + dj * l.step[1] + dk * l.step[2]) * kC;
          Double8 v8;
          Double2 v2;
          __builtin_memcpy(&v8, v, sizeof v8);
          __builtin_memcpy(&v2, v + 8, sizeof v2);
          low += wm * v8;
          high += wm * v2;
        }
    __builtin_memcpy(out[q], &low, sizeof low);
    __builtin_memcpy(out[q] + 8, &high, sizeof high);
  }
}


}  // namespace gf::coupling
