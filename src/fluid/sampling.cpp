#include "fluid/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "parallel/reductions.hpp"

namespace gf::fluid {

namespace {

/// Index and weight of the cell centres bracketing coordinate x along axis a (clamped).
std::pair<int, double> bracket(const CartesianGrid& g, int a, double x) {
  const double s = (x - g.origin[a]) / g.spacing[a] - 0.5;
  const int n = g.cells[a];
  if (n == 1) return {0, 0.0};
  const int i = std::clamp(static_cast<int>(std::floor(s)), 0, n - 2);
  return {i, std::clamp(s - i, 0.0, 1.0)};
}

/// Trilinear interpolation of the cell field f at p on the whole grid G, evaluated by the rank
/// owning the lower corner cell (local indices: global minus offset; the upper corner may be a
/// ghost); 0 on the other ranks (their sum is then the value).
double trilinearPart(const Solver& s, const Field& f, const Vec3& p) {
  const CartesianGrid& G = s.globalGrid();
  const auto [i, wx] = bracket(G, 0, p.x);
  const auto [j, wy] = bracket(G, 1, p.y);
  const auto [k, wz] = bracket(G, 2, p.z);
  if (!ownsCellAlong(s, 0, i) || !ownsCellAlong(s, 1, j) || !ownsCellAlong(s, 2, k)) return 0.0;
  const int li = localIndex(s, 0, i), lj = localIndex(s, 1, j), lk = localIndex(s, 2, k);
  const int di = G.cells[0] > 1, dj = G.cells[1] > 1, dk = G.cells[2] > 1;
  double v = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, d = (c >> 2) & 1;
    const double w = (a ? wx : 1 - wx) * (b ? wy : 1 - wy) * (d ? wz : 1 - wz);
    if (w != 0.0) v += w * f(li + a * di, lj + b * dj, lk + d * dk);
  }
  return v;
}

}  // namespace

double sumOverRanks(const Solver& s, double local) {
  const parallel::RankReductionScope ranks(s.decomposition());
  return sumAcrossRanks(local);
}

std::pair<double, double> sumOverRanks(const Solver& s, std::pair<double, double> local) {
  const parallel::RankReductionScope ranks(s.decomposition());
  return sumAcrossRanks(local);
}

double maxOverRanks(const Solver& s, double local) {
  const parallel::RankReductionScope ranks(s.decomposition());
  return maxAcrossRanks(local);
}

double minOverRanks(const Solver& s, double local) { return -maxOverRanks(s, -local); }

double planeMeanPressure(const Solver& s, int axis, double position) {
  const CartesianGrid& g = s.grid();
  const CartesianGrid& G = s.globalGrid();
  const auto [i0, w] = bracket(G, axis, position);
  const int b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
  double sum = 0.0, count = 0.0;
  // (the ranks whose box holds the lower layer; the upper one may be their ghost layer)
  if (ownsCellAlong(s, axis, i0))
    for (int q = 0; q < g.cells[b2]; ++q)
      for (int p = 0; p < g.cells[b1]; ++p) {
        int lo[3], hi[3];
        lo[axis] = localIndex(s, axis, i0);
        hi[axis] = localIndex(s, axis, std::min(i0 + 1, G.cells[axis] - 1));
        lo[b1] = hi[b1] = p;
        lo[b2] = hi[b2] = q;
        if (s.blocked(lo[0], lo[1], lo[2]) || s.blocked(hi[0], hi[1], hi[2])) continue;
        sum += (1 - w) * s.pressure()(lo[0], lo[1], lo[2]) + w * s.pressure()(hi[0], hi[1], hi[2]);
        count += 1.0;
      }
  std::tie(sum, count) = sumOverRanks(s, std::pair<double, double>{sum, count});
  return count > 0 ? sum / count : 0.0;
}

double flowRate(const Solver& s, int axis, double position) {
  const CartesianGrid& g = s.grid();
  const CartesianGrid& G = s.globalGrid();
  const int f = std::clamp(static_cast<int>(std::lround((position - G.origin[axis]) / G.spacing[axis])), 0,
                           G.cells[axis]);
  const int b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
  const double area = g.cellVolume() / g.spacing[axis];
  const Field& eps = s.couplingFields().voidFraction;
  double q = 0.0;
  // (the rank whose box holds the cell above the face, or below the last face)
  if (ownsCellAlong(s, axis, std::min(f, G.cells[axis] - 1)))
    for (int c2 = 0; c2 < g.cells[b2]; ++c2)
      for (int c1 = 0; c1 < g.cells[b1]; ++c1) {
        int idx[3], lo[3], hi[3];
        idx[axis] = localIndex(s, axis, f);
        idx[b1] = c1;
        idx[b2] = c2;
        for (int a = 0; a < 3; ++a) lo[a] = hi[a] = idx[a];
        lo[axis] = localIndex(s, axis, std::max(f - 1, 0));
        hi[axis] = localIndex(s, axis, std::min(f, G.cells[axis] - 1));
        const double epsF = 0.5 * (eps(lo[0], lo[1], lo[2]) + eps(hi[0], hi[1], hi[2]));
        q += epsF * s.velocity(axis)(idx[0], idx[1], idx[2]) * area;
      }
  return sumOverRanks(s, q);
}

double kineticEnergy(const Solver& s) {
  const CartesianGrid& g = s.grid();
  Field u[3];
  s.cellVelocity(u);
  const Field& eps = s.couplingFields().voidFraction;
  double e = 0.0;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i)
        e += eps(i, j, k) * (u[0](i, j, k) * u[0](i, j, k) + u[1](i, j, k) * u[1](i, j, k) + u[2](i, j, k) * u[2](i, j, k));
  if (s.vofEnabled()) {  // (the mixture density of each cell)
    const Field& rho = s.mixtureDensity();
    e = 0.0;
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i)
          e += rho(i, j, k) * eps(i, j, k) *
               (u[0](i, j, k) * u[0](i, j, k) + u[1](i, j, k) * u[1](i, j, k) + u[2](i, j, k) * u[2](i, j, k));
    return sumOverRanks(s, 0.5 * e * g.cellVolume());
  }
  return sumOverRanks(s, 0.5 * s.density() * e * g.cellVolume());
}

double maxCellSpeed(const Solver& s) {
  const CartesianGrid& g = s.grid();
  Field u[3];
  s.cellVelocity(u);
  double m = 0.0;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i)
        m = std::max(m, std::sqrt(u[0](i, j, k) * u[0](i, j, k) + u[1](i, j, k) * u[1](i, j, k) +
                                  u[2](i, j, k) * u[2](i, j, k)));
  return maxOverRanks(s, m);
}

std::vector<double> lineValues(const Solver& s, const Field& f, int axis, const Vec3& point) {
  const CartesianGrid& G = s.globalGrid();
  const bool distributed = s.decomposition().distributed();
  std::vector<double> out;
  for (int c = 0; c < G.cells[axis]; ++c) {
    Vec3 x = point;
    x[axis] = G.origin[axis] + (c + 0.5) * G.spacing[axis];
    const double part = trilinearPart(s, f, x);
    out.push_back(distributed ? sumOverRanks(s, part) : part);
  }
  return out;
}

double lastCrossing(const std::vector<double>& position, const std::vector<double>& values, double level) {
  const std::size_t n = values.size();
  if (n == 0) return 0.0;
  const double h = n > 1 ? position[1] - position[0] : 0.0;
  for (std::size_t c = n - 1; c-- > 0;)
    if (values[c] >= level && values[c + 1] < level) {
      const double w = (values[c] - level) / (values[c] - values[c + 1]);
      return position[c] + w * (position[c + 1] - position[c]);
    }
  return values[n - 1] >= level ? position[n - 1] : position[0] - 0.5 * h;
}

std::array<double, 4> probe(const Solver& s, const Vec3& point) {
  Field u[3];
  s.cellVelocity(u);
  std::array<double, 4> v{trilinearPart(s, u[0], point), trilinearPart(s, u[1], point),
                          trilinearPart(s, u[2], point), trilinearPart(s, s.pressure(), point)};
  if (s.decomposition().distributed())
    for (double& x : v) x = sumOverRanks(s, x);
  return v;
}

LineProfile lineProfile(const Solver& s, int axis, const Vec3& point) {
  Field u[3];
  s.cellVelocity(u);
  const CartesianGrid& G = s.globalGrid();
  const Field& eps = s.couplingFields().voidFraction;
  const bool distributed = s.decomposition().distributed();
  auto value = [&](const Field& f, const Vec3& x) {
    const double part = trilinearPart(s, f, x);
    return distributed ? sumOverRanks(s, part) : part;
  };
  LineProfile out;
  const int n = G.cells[axis];
  out.position.reserve(n);
  for (int c = 0; c < n; ++c) {
    // On the cell centre along the axis, so the weight along it is 0 and the other two
    // directions interpolate between the centres nearest to `point`.
    Vec3 x = point;
    x[axis] = G.origin[axis] + (c + 0.5) * G.spacing[axis];
    out.position.push_back(x[axis]);
    out.velocity.push_back({value(u[0], x), value(u[1], x), value(u[2], x)});
    out.pressure.push_back(value(s.pressure(), x));
    out.voidFraction.push_back(value(eps, x));
  }
  return out;
}

}  // namespace gf::fluid
