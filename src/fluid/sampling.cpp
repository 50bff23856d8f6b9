#include "fluid/sampling.hpp"

#include <algorithm>
#include <cmath>

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

double trilinear(const Field& f, const CartesianGrid& g, const Vec3& p) {
  const auto [i, wx] = bracket(g, 0, p.x);
  const auto [j, wy] = bracket(g, 1, p.y);
  const auto [k, wz] = bracket(g, 2, p.z);
  const int di = g.cells[0] > 1, dj = g.cells[1] > 1, dk = g.cells[2] > 1;
  double v = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, d = (c >> 2) & 1;
    const double w = (a ? wx : 1 - wx) * (b ? wy : 1 - wy) * (d ? wz : 1 - wz);
    if (w != 0.0) v += w * f(i + a * di, j + b * dj, k + d * dk);
  }
  return v;
}

}  // namespace

double planeMeanPressure(const Solver& s, int axis, double position) {
  const CartesianGrid& g = s.grid();
  const auto [i0, w] = bracket(g, axis, position);
  const int b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
  double sum = 0.0, count = 0.0;
  for (int q = 0; q < g.cells[b2]; ++q)
    for (int p = 0; p < g.cells[b1]; ++p) {
      int lo[3], hi[3];
      lo[axis] = i0;
      hi[axis] = std::min(i0 + 1, g.cells[axis] - 1);
      lo[b1] = hi[b1] = p;
      lo[b2] = hi[b2] = q;
      if (s.blocked(lo[0], lo[1], lo[2]) || s.blocked(hi[0], hi[1], hi[2])) continue;
      sum += (1 - w) * s.pressure()(lo[0], lo[1], lo[2]) + w * s.pressure()(hi[0], hi[1], hi[2]);
      count += 1.0;
    }
  return count > 0 ? sum / count : 0.0;
}

double flowRate(const Solver& s, int axis, double position) {
  const CartesianGrid& g = s.grid();
  const int f = std::clamp(static_cast<int>(std::lround((position - g.origin[axis]) / g.spacing[axis])), 0,
                           g.cells[axis]);
  const int b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
  const double area = g.cellVolume() / g.spacing[axis];
  const Field& eps = s.couplingFields().voidFraction;
  double q = 0.0;
  for (int c2 = 0; c2 < g.cells[b2]; ++c2)
    for (int c1 = 0; c1 < g.cells[b1]; ++c1) {
      int idx[3], lo[3], hi[3];
      idx[axis] = f;
      idx[b1] = c1;
      idx[b2] = c2;
      for (int a = 0; a < 3; ++a) lo[a] = hi[a] = idx[a];
      lo[axis] = std::max(f - 1, 0);
      hi[axis] = std::min(f, g.cells[axis] - 1);
      const double epsF = 0.5 * (eps(lo[0], lo[1], lo[2]) + eps(hi[0], hi[1], hi[2]));
      q += epsF * s.velocity(axis)(idx[0], idx[1], idx[2]) * area;
    }
  return q;
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
  return 0.5 * s.density() * e * g.cellVolume();
}

std::array<double, 4> probe(const Solver& s, const Vec3& point) {
  Field u[3];
  s.cellVelocity(u);
  const CartesianGrid& g = s.grid();
  return {trilinear(u[0], g, point), trilinear(u[1], g, point), trilinear(u[2], g, point),
          trilinear(s.pressure(), g, point)};
}

LineProfile lineProfile(const Solver& s, int axis, const Vec3& point) {
  Field u[3];
  s.cellVelocity(u);
  const CartesianGrid& g = s.grid();
  const Field& eps = s.couplingFields().voidFraction;
  LineProfile out;
  const int n = g.cells[axis];
  out.position.reserve(n);
  for (int c = 0; c < n; ++c) {
    // On the cell centre along the axis, so the weight along it is 0 and the other two
    // directions interpolate between the centres nearest to `point`.
    Vec3 x = point;
    x[axis] = g.origin[axis] + (c + 0.5) * g.spacing[axis];
    out.position.push_back(x[axis]);
    out.velocity.push_back({trilinear(u[0], g, x), trilinear(u[1], g, x), trilinear(u[2], g, x)});
    out.pressure.push_back(trilinear(s.pressure(), g, x));
    out.voidFraction.push_back(trilinear(eps, g, x));
  }
  return out;
}

}  // namespace gf::fluid
