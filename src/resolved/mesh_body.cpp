#include "resolved/mesh_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "dem/walls/wall_primitive.hpp"

namespace gf::resolved {

namespace {
double signedVolume(const io::Triangle& t) { return dot(t[0], cross(t[1], t[2])) / 6.0; }
}  // namespace

double meshVolume(const std::vector<io::Triangle>& triangles) {
  double v = 0.0;
  for (const io::Triangle& t : triangles) v += signedVolume(t);
  return std::abs(v);
}

Vec3 meshCentroid(const std::vector<io::Triangle>& triangles) {
  double v = 0.0;
  Vec3 moment;
  for (const io::Triangle& t : triangles) {
    const double vt = signedVolume(t);
    v += vt;
    moment += vt * (t[0] + t[1] + t[2]) / 4.0;  // tetrahedron (0, a, b, c): centroid (a + b + c) / 4
  }
  return v != 0.0 ? moment / v : Vec3{};
}

std::vector<double> lineCrossings(const std::vector<io::Triangle>& triangles, const std::vector<std::uint32_t>& which,
                                  double y, double z) {
  // Edge function of the edge pq at (y, z) in the y-z plane, (q - p) x (X - p), computed with p and q
  // in a canonical order and negated if swapped: the two triangles that share the edge get the same
  // number with opposite signs, so a line passes on one side of it for both.
  auto edge = [y, z](const Vec3& p, const Vec3& q) {
    const bool swap = q.y < p.y || (q.y == p.y && q.z < p.z);
    const Vec3& a = swap ? q : p;
    const Vec3& b = swap ? p : q;
    const double e = (b.y - a.y) * (z - a.z) - (b.z - a.z) * (y - a.y);
    return swap ? -e : e;
  };
  std::vector<double> xs;
  for (std::uint32_t n : which) {
    const io::Triangle& t = triangles[n];
    const double w0 = edge(t[1], t[2]), w1 = edge(t[2], t[0]), w2 = edge(t[0], t[1]);
    const bool negative = w0 < 0.0 || w1 < 0.0 || w2 < 0.0, positive = w0 > 0.0 || w1 > 0.0 || w2 > 0.0;
    if (negative && positive) continue;  // the line misses the triangle
    const double sum = w0 + w1 + w2;     // twice the projected area (signed)
    if (sum == 0.0) continue;            // parallel to x
    xs.push_back((w0 * t[0].x + w1 * t[1].x + w2 * t[2].x) / sum);
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

MeshBody::MeshBody(std::vector<io::Triangle> triangles, const CartesianGrid& grid, int samples)
    : triangles_(std::move(triangles)), grid_(grid), samples_(samples) {
  if (triangles_.empty()) throw Error("resolved stl body: the mesh has no triangles");
  if (samples_ < 2 || samples_ % 2 != 0) throw Error("resolved stl body: samples per cell must be even and >= 2");
  lo_ = hi_ = triangles_[0][0];
  for (const io::Triangle& t : triangles_)
    for (const Vec3& v : t)
      for (int a = 0; a < 3; ++a) {
        lo_[a] = std::min(lo_[a], v[a]);
        hi_[a] = std::max(hi_[a], v[a]);
      }
  volume_ = meshVolume(triangles_);
  centroid_ = meshCentroid(triangles_);
  const Vec3 h = grid_.spacing;
  const double n = samples_;
  // A generic offset of the lines, far below the sample spacing (irrational multiples of 1e-7 of it).
  shiftY_ = 3.14159265358979e-7 * h.y / n;
  shiftZ_ = 2.71828182845905e-7 * h.z / n;

  // Triangle bins over y-z, one cell of the grid each.
  binOrigin_ = lo_;
  for (int a = 0; a < 2; ++a)
    bins_[a] = static_cast<int>(std::floor((hi_[a + 1] - lo_[a + 1]) / h[a + 1])) + 1;
  binTriangles_.assign(static_cast<std::size_t>(bins_[0]) * bins_[1], {});
  auto binIndex = [&](double v, int a) {
    return std::clamp(static_cast<int>(std::floor((v - binOrigin_[a + 1]) / h[a + 1])), 0, bins_[a] - 1);
  };
  for (std::uint32_t q = 0; q < triangles_.size(); ++q) {
    const io::Triangle& t = triangles_[q];
    const int y0 = binIndex(std::min({t[0].y, t[1].y, t[2].y}), 0), y1 = binIndex(std::max({t[0].y, t[1].y, t[2].y}), 0);
    const int z0 = binIndex(std::min({t[0].z, t[1].z, t[2].z}), 1), z1 = binIndex(std::max({t[0].z, t[1].z, t[2].z}), 1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int iz = z0; iz <= z1; ++iz) binTriangles_[static_cast<std::size_t>(iy) * bins_[1] + iz].push_back(q);
  }

  // The half cells counted: the mesh's extent and a cell around it, within this box and a cell
  // around it (the control volumes of its boundary faces reach half a cell out).
  for (int a = 0; a < 3; ++a) {
    const int meshFirst = static_cast<int>(std::floor(2.0 * (lo_[a] - grid_.origin[a]) / h[a])) - 2;
    const int meshEnd = static_cast<int>(std::ceil(2.0 * (hi_[a] - grid_.origin[a]) / h[a])) + 2;
    first_[a] = std::max(meshFirst, -2);
    extent_[a] = std::max(0, std::min(meshEnd, 2 * grid_.cells[a] + 2) - first_[a]);
  }
  counts_.assign(static_cast<std::size_t>(extent_[0]) * extent_[1] * extent_[2], 0);
  if (counts_.empty()) return;
  const int half = samples_ / 2;  // samples per half cell along an axis
  const double dx = h.x / n;
  const double x0 = grid_.origin.x + (first_[0] * half + 0.5) * dx;
  std::vector<std::uint8_t> inside;
  for (int hz = 0; hz < extent_[2]; ++hz)
    for (int mz = 0; mz < half; ++mz) {
      const double z = grid_.origin.z + ((first_[2] + hz) * half + mz + 0.5) * h.z / n;
      for (int hy = 0; hy < extent_[1]; ++hy)
        for (int my = 0; my < half; ++my) {
          const double y = grid_.origin.y + ((first_[1] + hy) * half + my + 0.5) * h.y / n;
          classifyRow(x0, dx, extent_[0] * half, y, z, inside);
          std::uint32_t* row = &counts_[(static_cast<std::size_t>(hz) * extent_[1] + hy) * extent_[0]];
          for (int s = 0; s < extent_[0] * half; ++s) row[s / half] += inside[s];
        }
    }
}

const std::vector<std::uint32_t>& MeshBody::binOf(double y, double z) const {
  const int iy = static_cast<int>(std::floor((y - binOrigin_.y) / grid_.spacing.y));
  const int iz = static_cast<int>(std::floor((z - binOrigin_.z) / grid_.spacing.z));
  if (y < lo_.y || y > hi_.y || z < lo_.z || z > hi_.z || iy < 0 || iz < 0 || iy >= bins_[0] || iz >= bins_[1])
    return noTriangles_;
  return binTriangles_[static_cast<std::size_t>(iy) * bins_[1] + iz];
}

void MeshBody::classifyRow(double x0, double dx, int count, double y, double z, std::vector<std::uint8_t>& inside) const {
  inside.assign(static_cast<std::size_t>(count), 0);
  const double ys = y + shiftY_, zs = z + shiftZ_;
  const std::vector<std::uint32_t>& which = binOf(ys, zs);
  if (which.empty()) return;
  const std::vector<double> xs = lineCrossings(triangles_, which, ys, zs);
  std::size_t next = 0;
  bool in = false;
  for (int s = 0; s < count; ++s) {
    const double x = x0 + s * dx;
    while (next < xs.size() && xs[next] < x) {
      in = !in;
      ++next;
    }
    inside[static_cast<std::size_t>(s)] = in ? 1 : 0;
  }
}

double MeshBody::fraction(const Vec3& lo, const Vec3& hi) const {
  const Vec3 h = grid_.spacing;
  std::array<int, 3> H{};
  bool onLattice = true;
  for (int a = 0; a < 3; ++a) {
    if (hi[a] <= lo_[a] || lo[a] >= hi_[a]) return 0.0;  // clear of the mesh's extent
    const double l = 2.0 * (lo[a] - grid_.origin[a]) / h[a], u = 2.0 * (hi[a] - grid_.origin[a]) / h[a];
    H[a] = static_cast<int>(std::lround(l));
    if (std::abs(l - H[a]) > 1e-6 || std::abs(u - (H[a] + 2)) > 1e-6) onLattice = false;
  }
  const double n = samples_;
  if (onLattice) {
    std::uint64_t sum = 0;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dxh = 0; dxh < 2; ++dxh) {
          const int i = H[0] + dxh - first_[0], j = H[1] + dy - first_[1], k = H[2] + dz - first_[2];
          if (i < 0 || j < 0 || k < 0 || i >= extent_[0] || j >= extent_[1] || k >= extent_[2]) continue;
          sum += counts_[(static_cast<std::size_t>(k) * extent_[1] + j) * extent_[0] + i];
        }
    return static_cast<double>(sum) / (n * n * n);
  }
  // Any other box: its own n^3 samples.
  const Vec3 d = (hi - lo) / n;
  std::vector<std::uint8_t> inside;
  std::uint64_t sum = 0;
  for (int mz = 0; mz < samples_; ++mz)
    for (int my = 0; my < samples_; ++my) {
      classifyRow(lo.x + 0.5 * d.x, d.x, samples_, lo.y + (my + 0.5) * d.y, lo.z + (mz + 0.5) * d.z, inside);
      for (std::uint8_t v : inside) sum += v;
    }
  return static_cast<double>(sum) / (n * n * n);
}

bool MeshBody::contains(const Vec3& p) const {
  for (int a = 0; a < 3; ++a)
    if (p[a] < lo_[a] || p[a] > hi_[a]) return false;
  std::vector<std::uint8_t> inside;
  classifyRow(p.x, 0.0, 1, p.y, p.z, inside);
  return inside[0] != 0;
}

double MeshBody::distance(const Vec3& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const io::Triangle& t : triangles_)
    best = std::min(best, normSquared(p - dem::closestPointOnTriangle(p, t[0], t[1], t[2])));
  return std::sqrt(best);
}

}  // namespace gf::resolved
