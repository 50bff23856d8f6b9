#include "fluid/solid_mesh.hpp"

#include <algorithm>

namespace gf::fluid {

SolidMesh::SolidMesh(std::vector<std::array<Vec3, 3>> triangles) : triangles_(std::move(triangles)) {
  if (triangles_.empty()) return;
  lo_ = hi_ = triangles_[0][0];
  for (const auto& t : triangles_)
    for (const Vec3& v : t)
      for (int a = 0; a < 3; ++a) {
        lo_[a] = std::min(lo_[a], v[a]);
        hi_[a] = std::max(hi_[a], v[a]);
      }
}

double SolidMesh::windingNumber(const Vec3& p) const {
  double sum = 0.0;
  for (const auto& t : triangles_) sum += triangleSolidAngle(t[0] - p, t[1] - p, t[2] - p);
  return sum / (4.0 * std::numbers::pi);
}

bool SolidMesh::contains(const Vec3& p) const {
  if (triangles_.empty()) return false;
  for (int a = 0; a < 3; ++a)
    if (p[a] < lo_[a] || p[a] > hi_[a]) return false;
  return std::abs(windingNumber(p)) > 0.5;
}

}  // namespace gf::fluid
