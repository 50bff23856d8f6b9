// Infinite plane wall.
#include "dem/walls/wall.hpp"

namespace gf::dem {
namespace {
class PlaneWall final : public Wall {
 public:
  explicit PlaneWall(Params& p) {
    point_ = p.vec3({"point", "m", "plane: a point on the plane"}, {});
    const Vec3 n = p.vec3({"normal", "-", "plane: normal pointing into the particle region"}, {0, 0, 1});
    if (!p.documenting() && norm(n) == 0.0) p.fail("normal", "[0, 0, 0]", "a non-zero vector");
    normal_ = normalized(n);
  }
  std::vector<WallPrimitive> primitives() const override {
    WallPrimitive w;
    w.kind = PrimitiveKind::Plane;
    w.a = point_;
    w.b = normal_;
    return {w};
  }

 private:
  Vec3 point_, normal_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Wall, gf::dem::PlaneWall, "plane", "infinite plane, one-sided (point, normal)")
