// Flat disk or annulus (e.g. a silo bottom with a circular orifice): the axisymmetric primitive
// with zero length, generator from r = inner_radius to r = outer_radius.
#include "dem/walls/wall.hpp"

namespace gf::dem {
namespace {
class DiskWall final : public Wall {
 public:
  explicit DiskWall(Params& p) {
    centre_ = p.vec3({"center", "m", "disk: centre"}, {});
    normal_ = p.vec3({"normal", "-", "disk: normal (either side is a contact side)"}, {0, 0, 1});
    inner_ = p.real({"inner_radius", "m", "disk: radius of the central hole (0: full disk)", Range::nonNegative()}, 0.0);
    outer_ = p.real({"outer_radius", "m", "disk: outer radius", Range::positive()}, 1.0);
    if (!p.documenting() && norm(normal_) == 0.0) p.fail("normal", "[0, 0, 0]", "a non-zero vector");
    if (!p.documenting() && !(outer_ > inner_)) p.fail("outer_radius", "not above inner_radius", "outer > inner");
  }
  std::vector<WallPrimitive> primitives() const override {
    WallPrimitive w;
    w.kind = PrimitiveKind::Axisymmetric;
    w.a = centre_;
    w.b = normalized(normal_);
    w.r0 = inner_;
    w.r1 = outer_;
    w.length = 0.0;
    return {w};
  }

 private:
  Vec3 centre_, normal_;
  double inner_ = 0.0, outer_ = 1.0;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Wall, gf::dem::DiskWall, "disk",
                  "flat disk or annulus (center, normal, inner_radius, outer_radius), e.g. a silo bottom with orifice")
