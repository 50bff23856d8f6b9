// Axis-aligned box holding the particles inside (six inward-facing planes).
#include "dem/walls/wall.hpp"

namespace gf::dem {
namespace {
class BoxWall final : public Wall {
 public:
  explicit BoxWall(Params& p) {
    min_ = p.vec3({"min", "m", "box: lower corner"}, {0, 0, 0});
    max_ = p.vec3({"max", "m", "box: upper corner"}, {1, 1, 1});
    for (int a = 0; a < 3; ++a)
      if (!p.documenting() && !(max_[a] > min_[a])) p.fail("max", "a corner not above 'min'", "max > min in x, y, z");
    const std::vector<double> open = p.reals({"open", "-", "box: faces left out, flags [-x, +x, -y, +y, -z, +z]",
                                              Range::between(0, 1)},
                                             {0, 0, 0, 0, 0, 0});
    if (open.size() != 6) p.fail("open", std::to_string(open.size()) + " values", "6 flags");
    for (int f = 0; f < 6; ++f) open_[f] = open[f] != 0.0;
  }
  std::vector<WallPrimitive> primitives() const override {
    std::vector<WallPrimitive> out;
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        if (open_[2 * a + side]) continue;
        WallPrimitive w;
        w.kind = PrimitiveKind::Plane;
        w.a = side == 0 ? min_ : max_;
        Vec3 n{};
        n[a] = side == 0 ? 1.0 : -1.0;
        w.b = n;
        out.push_back(w);
      }
    return out;
  }

 private:
  Vec3 min_, max_;
  bool open_[6] = {};
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Wall, gf::dem::BoxWall, "box", "axis-aligned box, particles inside (min, max, open)")
