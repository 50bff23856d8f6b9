#pragma once
// Geometric primitives that walls are made of, and the distance from a sphere centre to each.
// A plane is one-sided (particles on the side its normal points to); triangles and axisymmetric
// segments (cylinders, cones/frusta) use the unsigned distance, so particles touch them from
// either side (inner and outer cylinders are the same primitive).
#include <cmath>
#include <cstdint>

#include "core/vec3.hpp"

namespace gf::dem {

enum class PrimitiveKind : std::int32_t { Plane, Triangle, Axisymmetric };

struct WallPrimitive {
  PrimitiveKind kind = PrimitiveKind::Plane;
  std::int32_t wall = 0;  // index of the owning wall
  // Plane: a = point, b = unit normal. Triangle: a, b, c = vertices.
  // Axisymmetric: a = point on the axis at s = 0, b = unit axis; radius r0 at s = 0, r1 at s = length.
  Vec3 a, b, c;
  double r0 = 0.0, r1 = 0.0, length = 0.0;
  bool active = true;  // false once the wall's `active_until` time has passed
};

struct WallDistance {
  double distance;  // from the sphere centre to the surface (signed for planes), m
  Vec3 normal;      // unit, from the surface towards the centre
};

/// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, sec. 5.1.5).
/// `onFace` (if given) is set to true when the point lies inside the face (not on an edge or vertex).
inline Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                   bool* onFace = nullptr) {
  if (onFace) *onFace = false;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  if (onFace) *onFace = true;
  const double denom = 1.0 / (va + vb + vc);
  return a + (vb * denom) * ab + (vc * denom) * ac;
}

/// True if point x lies on triangle w (within `tolerance`, m).
inline bool pointOnTriangle(const WallPrimitive& w, const Vec3& x, double tolerance) {
  return normSquared(x - closestPointOnTriangle(x, w.a, w.b, w.c)) <= tolerance * tolerance;
}

inline WallDistance distanceToPrimitive(const WallPrimitive& w, const Vec3& x) {
  switch (w.kind) {
    case PrimitiveKind::Plane:
      return {dot(x - w.a, w.b), w.b};
    case PrimitiveKind::Triangle: {
      const Vec3 d = x - closestPointOnTriangle(x, w.a, w.b, w.c);
      const double dist = norm(d);
      return {dist, dist > 0.0 ? d / dist : Vec3{}};
    }
    case PrimitiveKind::Axisymmetric: {
      // Meridional plane (s along the axis, rho radial): closest point on the generator segment.
      const Vec3 rel = x - w.a;
      const double s = dot(rel, w.b);
      const Vec3 radial = rel - s * w.b;
      const double rho = norm(radial);
      const Vec3 er = rho > 0.0 ? radial / rho : Vec3{};
      const double ds = w.length, dr = w.r1 - w.r0;
      double t = (s * ds + (rho - w.r0) * dr) / (ds * ds + dr * dr);
      t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
      const double gs = s - t * ds, gr = rho - (w.r0 + t * dr);
      const double dist = std::sqrt(gs * gs + gr * gr);
      return {dist, dist > 0.0 ? (gs / dist) * w.b + (gr / dist) * er : Vec3{}};
    }
  }
  return {1e300, {}};
}

}  // namespace gf::dem
