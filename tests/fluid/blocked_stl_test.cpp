// Blocked cells from closed STL meshes: a cell is blocked when its centre is inside the
// mesh (generalised winding number, Jacobson et al. 2013). An STL cube, ASCII or binary, scaled
// from mm, must block exactly the cells of the equivalent `shape: box`.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "fluid/solid_mesh.hpp"
#include "../io/stl_test_writer.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

using Tri = gf::testing::StlTriangle;
using gf::testing::writeStl;

/// The 12 triangles of the box [lo, hi], outward-oriented.
std::vector<Tri> boxTriangles(const Vec3& lo, const Vec3& hi) {
  auto corner = [&](int m) { return Vec3{(m & 1) ? hi.x : lo.x, (m & 2) ? hi.y : lo.y, (m & 4) ? hi.z : lo.z}; };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<Tri> t;
  for (const auto& q : quads) {
    t.push_back({corner(q[0]), corner(q[1]), corner(q[2])});
    t.push_back({corner(q[0]), corner(q[2]), corner(q[3])});
  }
  return t;
}

TEST(SolidMesh, WindingNumberIsOneInsideZeroOutsideAnyOrientation) {
  auto tris = boxTriangles({0, 0, 0}, {1, 2, 3});
  EXPECT_NEAR(SolidMesh(tris).windingNumber({0.5, 1.0, 1.0}), 1.0, 1e-12);
  EXPECT_NEAR(SolidMesh(tris).windingNumber({1.5, 1.0, 1.0}), 0.0, 1e-12);
  EXPECT_NEAR(SolidMesh(tris).windingNumber({0.9, 1.9, 2.9}), 1.0, 1e-12);
  for (auto& t : tris) std::swap(t[1], t[2]);  // inward orientation: -1 inside, still "inside"
  EXPECT_NEAR(SolidMesh(tris).windingNumber({0.5, 1.0, 1.0}), -1.0, 1e-12);
  EXPECT_TRUE(SolidMesh(tris).contains({0.5, 1.0, 1.0}));
  EXPECT_FALSE(SolidMesh(tris).contains({0.5, 1.0, 3.5}));
}

std::vector<int> blockedCells(const std::string& blockedEntry) {
  auto c = test::makeCase("domain: {min: [0, 0, 0], max: [1, 1, 1]}\nfluid:\n  cells: [10, 12, 14]\n  blocked:\n" +
                          blockedEntry);
  const auto& g = c.solver->grid();
  std::vector<int> out;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) out.push_back(c.solver->blocked(i, j, k) ? 1 : 0);
  return out;
}

TEST(BlockedStl, CubeMeshBlocksTheCellsOfTheEquivalentBox) {
  const auto dir = std::filesystem::temp_directory_path() / "grainflow_fluid_stl";
  std::filesystem::create_directories(dir);
  // Cube in mm (scale 0.001), shifted by the offset to [0.3, 0.7] x [0.2, 0.65] x [0.33, 0.8] m.
  const auto tris = boxTriangles({0, 0, 0}, {400, 450, 470});
  writeStl(dir / "cube_ascii.stl", tris, false);
  writeStl(dir / "cube_binary.stl", tris, true);
  const auto box = blockedCells("    - {shape: box, min: [0.3, 0.2, 0.33], max: [0.7, 0.65, 0.8]}\n");
  int count = 0;
  for (int v : box) count += v;
  EXPECT_EQ(count, 4 * 6 * 6);  // centres inside: x 0.35..0.65, y 0.208..0.625, z 0.393..0.750
  for (const char* name : {"cube_ascii.stl", "cube_binary.stl"}) {
    const auto stl = blockedCells("    - {shape: stl, file: " + (dir / name).string() +
                                  ", scale: 0.001, offset: [0.3, 0.2, 0.33]}\n");
    EXPECT_EQ(stl, box) << name;
  }
}

TEST(BlockedStl, MissingFileIsACaseError) {
  EXPECT_THROW(blockedCells("    - {shape: stl, file: /nonexistent/mesh.stl}\n"), CaseError);
}

}  // namespace
}  // namespace gf::fluid
