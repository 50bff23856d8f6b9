#pragma once
// Closed triangle mesh (from an STL file) as a solid: inside test by the generalised winding
// number, w(p) = sum over triangles of the solid angle they subtend at p / (4 pi), which is +-1
// inside a closed mesh and 0 outside whatever the triangle orientation or convexity
// (Jacobson et al. 2013, "Robust inside-outside segmentation using generalized winding numbers").
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/vec3.hpp"

namespace gf::fluid {

/// Signed solid angle of triangle (a, b, c) seen from the origin (a, b, c relative to the point):
/// tan(Omega / 2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)
/// (Van Oosterom and Strackee 1983, IEEE Trans. Biomed. Eng. 30, eq. 8).
inline double triangleSolidAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = norm(a), lb = norm(b), lc = norm(c);
  const double numerator = dot(a, cross(b, c));
  const double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2.0 * std::atan2(numerator, denominator);
}

class SolidMesh {
 public:
  explicit SolidMesh(std::vector<std::array<Vec3, 3>> triangles);
  /// |winding number| > 1/2: inside the closed mesh.
  bool contains(const Vec3& p) const;
  double windingNumber(const Vec3& p) const;
  const Vec3& lower() const { return lo_; }
  const Vec3& upper() const { return hi_; }

 private:
  std::vector<std::array<Vec3, 3>> triangles_;
  Vec3 lo_, hi_;  // bounding box: points outside it are outside
};

}  // namespace gf::fluid
