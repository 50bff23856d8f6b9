#include "coupling/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/parallel.hpp"
#include "core/reduction.hpp"
#include "parallel/halo.hpp"
#include "parallel/reductions.hpp"

namespace gf::coupling {
namespace {

/// Grids below this many cells are smoothed on the calling thread: a CG iteration on them takes a
/// few microseconds per pass, no more than opening a parallel region (the seed's tank drain has
/// 9,072 cells and smooths eight fields of 50-80 iterations per coupling step).
constexpr std::int64_t kSmoothingSerialBelow = 65536;

/// The smoothing's loops and sums: serial on small grids, threaded (fixed blocks) on large ones.
SumPolicy smoothingSums() { return {kSmoothingSerialBelow, false, false}; }
template <class Body>
void forSmoothing(std::int64_t cells, std::int64_t count, Body&& body) {
  if (cells < kSmoothingSerialBelow) {
    for (std::int64_t i = 0; i < count; ++i) body(i);
  } else {
    parallelFor(count, body);
  }
}

/// Interior cells as a compact vector (x fastest).
struct Compact {
  const GridTopology& t;
  std::size_t n() const { return t.grid.interiorCellCount(); }
  std::size_t at(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * t.grid.cells[1] + j) * t.grid.cells[0] + i;
  }
};

/// y = (I - l^2 L) x with the 7-point Laplacian, zero flux at walls, wrap at periodic boundaries.
/// x is copied into `work`, a field with ghost cells that hold what each neighbour term reads: the
/// neighbour rank's cells across a cut (decomposed grid), the other end's along an axis this box
/// wraps itself, and the boundary cell's own value at a wall (its term (x_c - x_c) / h^2 is 0: no
/// flux). The stencil then runs without a branch per neighbour (an axis of one cell that no
/// neighbour rank continues is left out).
void apply(const GridTopology& t, double l2, const std::vector<double>& x, std::vector<double>& y, Field& work) {
  const Compact c{t};
  const auto& n = t.grid.cells;
  const auto lines = static_cast<std::int64_t>(n[2]) * n[1];
  const auto cellCount = lines * n[0];
  forSmoothing(cellCount, lines, [&](std::int64_t kj) {
    const int k = static_cast<int>(kj / n[1]), j = static_cast<int>(kj % n[1]);
    std::copy_n(x.data() + c.at(0, j, k), n[0], &work(0, j, k));
  });
  if (t.distributed()) parallel::fillGhosts(work, *t.decomposition);
  bool active[3];
  for (int a = 0; a < 3; ++a) {
    active[a] = !(n[a] == 1 && !t.shared[a][0] && !t.shared[a][1]);
    if (!active[a]) continue;
    // The face ghosts of the sides without a neighbour rank: the wrapped cell or the cell itself.
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      if (t.shared[a][side]) continue;
      const int ghost = side == 0 ? -1 : n[a], source = t.periodic[a] ? (side == 0 ? n[a] - 1 : 0) : (side == 0 ? 0 : n[a] - 1);
      for (int q = 0; q < n[d]; ++q)
        for (int p = 0; p < n[b]; ++p) {
          int g[3], s[3];
          g[a] = ghost;
          s[a] = source;
          g[b] = s[b] = p;
          g[d] = s[d] = q;
          work(g[0], g[1], g[2]) = work(s[0], s[1], s[2]);
        }
    }
  }
  std::ptrdiff_t stride[3];
  double c2[3];  // 1 / h^2 per axis
  for (int a = 0; a < 3; ++a) {
    stride[a] = work.stride(a);
    c2[a] = 1.0 / (t.grid.spacing[a] * t.grid.spacing[a]);
  }
  const std::ptrdiff_t sx = stride[0], sy = stride[1], sz = stride[2];
  forSmoothing(cellCount, lines, [&](std::int64_t kj) {
    const int k = static_cast<int>(kj / n[1]), j = static_cast<int>(kj % n[1]);
    const double* w = &work(0, j, k);
    double* out = y.data() + c.at(0, j, k);
    if (active[0] && active[1] && active[2]) {  // (the usual case: one loop the compiler vectorises)
      for (int i = 0; i < n[0]; ++i) {
        const double xc = w[i];
        const double lap = (w[i - sx] + w[i + sx] - 2.0 * xc) * c2[0] + (w[i - sy] + w[i + sy] - 2.0 * xc) * c2[1] +
                           (w[i - sz] + w[i + sz] - 2.0 * xc) * c2[2];
        out[i] = xc - l2 * lap;
      }
      return;
    }
    for (int i = 0; i < n[0]; ++i) {
      const double xc = w[i];
      double lap = 0.0;
      for (int a = 0; a < 3; ++a)
        if (active[a]) lap += (w[i - stride[a]] + w[i + stride[a]] - 2.0 * xc) * c2[a];
      out[i] = xc - l2 * lap;
    }
  });
}

}  // namespace

SmoothingReport smoothField(const GridTopology& t, double l, Field& field) {
  SmoothingReport report;
  if (l <= 0.0) return report;
  const Compact c{t};
  const std::size_t n = c.n();
  const auto& cells = t.grid.cells;
  // on a decomposed grid the dot products and norms below are sums over the ranks
  std::optional<parallel::RankReductionScope> ranks;
  if (t.distributed()) ranks.emplace(*t.decomposition);
  Field work(t.grid);  // x or p with ghost cells (apply)
  std::vector<double> b(n), x(n), r(n), p(n), q(n);
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) b[c.at(i, j, k)] = field(i, j, k);
  // Conjugate gradients on the SPD matrix A = I - l^2 L (its eigenvalues lie in [1, 1 + 4 l^2 sum 1/h^2]).
  x = b;
  apply(t, l * l, x, q, work);
  const auto count = static_cast<std::int64_t>(n);
  forSmoothing(count, count, [&](std::int64_t i) { r[i] = b[i] - q[i]; });
  p = r;
  const double bNorm = gf::norm(b, smoothingSums());
  double rr = gf::dot(r, r, smoothingSums());
  const double tolerance = 1e-13 * (bNorm > 0.0 ? bNorm : 1.0);
  int it = 0;
  while (std::sqrt(rr) > tolerance && it < 10000) {
    apply(t, l * l, p, q, work);
    const double alpha = rr / gf::dot(p, q, smoothingSums());
    forSmoothing(count, count, [&](std::int64_t i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    });
    const double rrNew = gf::dot(r, r, smoothingSums());
    const double beta = rrNew / rr;
    rr = rrNew;
    forSmoothing(count, count, [&](std::int64_t i) { p[i] = r[i] + beta * p[i]; });
    ++it;
  }
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) field(i, j, k) = x[c.at(i, j, k)];
  report.iterations = it;
  report.relativeResidual = std::sqrt(rr) / (bNorm > 0.0 ? bNorm : 1.0);
  return report;
}

}  // namespace gf::coupling
