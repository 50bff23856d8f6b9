// Triangle-mesh wall from an ASCII or binary STL file.
#include <filesystem>

#include "dem/walls/wall.hpp"
#include "io/stl_reader.hpp"

namespace gf::dem {
namespace {
class StlWall final : public Wall {
 public:
  explicit StlWall(Params& p) {
    const std::string file = p.text({"file", "-", "stl: path of the STL file (relative to the case file)"}, "");
    const double scale = p.real({"scale", "-", "stl: factor applied to the coordinates (e.g. 0.001 for mm)",
                                 Range::positive()},
                                1.0);
    const Vec3 offset = p.vec3({"offset", "m", "stl: translation applied after scaling"}, {});
    if (p.documenting()) return;
    std::filesystem::path path(file);
    if (path.is_relative()) path = std::filesystem::path(p.fileName()).parent_path() / path;
    try {
      for (const io::Triangle& t : io::readStl(path.string())) {
        WallPrimitive w;
        w.kind = PrimitiveKind::Triangle;
        w.a = scale * t[0] + offset;
        w.b = scale * t[1] + offset;
        w.c = scale * t[2] + offset;
        triangles_.push_back(w);
      }
    } catch (const Error& e) {
      p.fail("file", "'" + file + "'", std::string("a readable STL file (") + e.what() + ")");
    }
  }
  std::vector<WallPrimitive> primitives() const override { return triangles_; }

 private:
  std::vector<WallPrimitive> triangles_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Wall, gf::dem::StlWall, "stl", "triangle mesh from an ASCII or binary STL file")
