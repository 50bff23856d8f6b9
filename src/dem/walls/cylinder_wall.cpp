// Finite cylinder (no caps); particles may be inside (drum, pipe) or outside (obstacle).
#include "dem/walls/wall.hpp"

namespace gf::dem {
namespace {
class CylinderWall final : public Wall {
 public:
  explicit CylinderWall(Params& p) {
    base_ = p.vec3({"base", "m", "cylinder: centre of the first end"}, {});
    const Vec3 axis = p.vec3({"axis", "m", "cylinder: vector from the first to the second end"}, {0, 0, 1});
    radius_ = p.real({"radius", "m", "cylinder: radius", Range::positive()}, 1.0);
    if (!p.documenting() && norm(axis) == 0.0) p.fail("axis", "[0, 0, 0]", "a non-zero vector");
    axis_ = axis;
  }
  std::vector<WallPrimitive> primitives() const override {
    WallPrimitive w;
    w.kind = PrimitiveKind::Axisymmetric;
    w.a = base_;
    w.b = normalized(axis_);
    w.r0 = w.r1 = radius_;
    w.length = norm(axis_);
    return {w};
  }

 private:
  Vec3 base_, axis_;
  double radius_ = 1.0;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Wall, gf::dem::CylinderWall, "cylinder",
                  "finite cylinder surface without caps (base, axis, radius); contact from inside or outside")
