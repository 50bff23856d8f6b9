#pragma once
// Walls: named geometry models (plane, box, cylinder, cone, stl), each one file registered with
// GF_REGISTER_MODEL(gf::dem::Wall, ...). A wall only produces primitives; the System moves them
// with the wall's prescribed translation/rotation and computes contacts in one loop.
#include <memory>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/registry.hpp"
#include "dem/walls/wall_primitive.hpp"

namespace gf::dem {

class Wall {
 public:
  virtual ~Wall() = default;
  /// Primitives in the reference (t = 0) position.
  virtual std::vector<WallPrimitive> primitives() const = 0;
};

/// Prescribed rigid motion: translation with `velocity`, rotation with `angularVelocity` about
/// `centre` (which moves with the wall).
struct WallMotion {
  Vec3 velocity;         // m/s
  Vec3 angularVelocity;  // rad/s
  Vec3 centre;           // m, at t = 0
};

/// Force and torque that the particles exert on one wall (torque about the wall's current centre).
struct WallLoad {
  std::string name;
  Vec3 force;   // N
  Vec3 torque;  // N m
};

/// Rotation of v by the rotation vector theta (Rodrigues' formula).
inline Vec3 rotate(const Vec3& v, const Vec3& theta) {
  const double angle = norm(theta);
  if (angle == 0.0) return v;
  const Vec3 k = theta / angle;
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * cross(k, v) + (1.0 - c) * dot(k, v) * k;
}

}  // namespace gf::dem
