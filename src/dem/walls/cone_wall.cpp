// Cone / frustum (hopper): radius varies linearly along the axis.
#include "dem/walls/wall.hpp"

namespace gf::dem {
namespace {
class ConeWall final : public Wall {
 public:
  explicit ConeWall(Params& p) {
    base_ = p.vec3({"base", "m", "cone: centre of the first end"}, {});
    axis_ = p.vec3({"axis", "m", "cone: vector from the first to the second end"}, {0, 0, 1});
    r0_ = p.real({"radius_base", "m", "cone: radius at the first end", Range::nonNegative()}, 0.0);
    r1_ = p.real({"radius_top", "m", "cone: radius at the second end", Range::nonNegative()}, 1.0);
    if (!p.documenting() && norm(axis_) == 0.0) p.fail("axis", "[0, 0, 0]", "a non-zero vector");
  }
  std::vector<WallPrimitive> primitives() const override {
    WallPrimitive w;
    w.kind = PrimitiveKind::Axisymmetric;
    w.a = base_;
    w.b = normalized(axis_);
    w.r0 = r0_;
    w.r1 = r1_;
    w.length = norm(axis_);
    return {w};
  }

 private:
  Vec3 base_, axis_;
  double r0_ = 0.0, r1_ = 1.0;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Wall, gf::dem::ConeWall, "cone",
                  "cone or frustum surface (base, axis, radius_base, radius_top), e.g. a hopper")
