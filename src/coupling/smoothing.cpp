#include "coupling/smoothing.hpp"

#include <cmath>
#include <optional>
#include <vector>

#include "core/reduction.hpp"
#include "coupling/loops.hpp"
#include "parallel/halo.hpp"
#include "parallel/reductions.hpp"

namespace gf::coupling {
namespace {

/// Interior cells as a compact vector (x fastest).
struct Compact {
  const GridTopology& t;
  std::size_t n() const { return t.grid.interiorCellCount(); }
  std::size_t at(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * t.grid.cells[1] + j) * t.grid.cells[0] + i;
  }
};

/// y = (I - l^2 L) x with the 7-point Laplacian, zero flux at walls, wrap at periodic boundaries.
/// `at(i, j, k)` reads x at a cell: interior, wrapped, or (decomposed grid) a ghost cell holding
/// the neighbour rank's value.
template <class At>
void applyWith(const GridTopology& t, double l2, At&& at, std::vector<double>& y) {
  const Compact c{t};
  const auto& n = t.grid.cells;
  forEachIndex(static_cast<std::int64_t>(n[2]) * n[1], n[0], [&](std::int64_t kj) {
    const int k = static_cast<int>(kj / n[1]);
    const int j = static_cast<int>(kj % n[1]);
    for (int i = 0; i < n[0]; ++i) {
      const int idx[3] = {i, j, k};
      const double xc = at(i, j, k);
      double lap = 0.0;
      for (int a = 0; a < 3; ++a) {
        if (n[a] == 1 && !t.shared[a][0] && !t.shared[a][1]) continue;
        const double h2 = t.grid.spacing[a] * t.grid.spacing[a];
        for (int s : {-1, 1}) {
          int nb[3] = {i, j, k};
          const int m = idx[a] + s;
          if ((m < 0 && !t.open(a, 0)) || (m >= n[a] && !t.open(a, 1))) continue;  // wall: no flux
          nb[a] = t.mapIndex(m, a);
          lap += (at(nb[0], nb[1], nb[2]) - xc) / h2;
        }
      }
      y[c.at(i, j, k)] = xc - l2 * lap;
    }
  });
}

/// applyWith on the compact vector x; on a decomposed grid through `work`, a field whose ghost
/// cells across the cuts receive the neighbours' values first (one exchange per product).
void apply(const GridTopology& t, double l2, const std::vector<double>& x, std::vector<double>& y, Field& work) {
  const Compact c{t};
  if (!t.distributed()) {
    applyWith(t, l2, [&](int i, int j, int k) { return x[c.at(i, j, k)]; }, y);
    return;
  }
  const auto& n = t.grid.cells;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) work(i, j, k) = x[c.at(i, j, k)];
  parallel::fillGhosts(work, *t.decomposition);
  applyWith(t, l2, [&](int i, int j, int k) { return work(i, j, k); }, y);
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
  Field work;  // (decomposed grid: x or p with the neighbours' ghost cells, apply)
  if (t.distributed()) work = Field(t.grid);
  std::vector<double> b(n), x(n), r(n), p(n), q(n);
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) b[c.at(i, j, k)] = field(i, j, k);
  // Conjugate gradients on the SPD matrix A = I - l^2 L (its eigenvalues lie in [1, 1 + 4 l^2 sum 1/h^2]).
  x = b;
  apply(t, l * l, x, q, work);
  for (std::size_t i = 0; i < n; ++i) r[i] = b[i] - q[i];
  p = r;
  const double bNorm = gf::norm(b, indexSums());
  double rr = gf::dot(r, r, indexSums());
  const double tolerance = 1e-13 * (bNorm > 0.0 ? bNorm : 1.0);
  int it = 0;
  while (std::sqrt(rr) > tolerance && it < 10000) {
    apply(t, l * l, p, q, work);
    const double alpha = rr / gf::dot(p, q, indexSums());
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    const double rrNew = gf::dot(r, r, indexSums());
    const double beta = rrNew / rr;
    rr = rrNew;
    for (std::size_t i = 0; i < n; ++i) p[i] = r[i] + beta * p[i];
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
