// Triangle-mesh (STL) walls: a sphere resting on an edge or a vertex shared by several triangles
// gets one contact (not one per triangle); a sphere in a concave groove keeps one per face.
// Reference: Hertz contact of a sphere on a rigid flat under its weight,
//   m g = 4/3 E* sqrt(R) d^(3/2), E* = E/(1 - nu^2) (Johnson 1985 eq. 4.22, rigid counterface).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "dem/wall_contact_list.hpp"
#include "dem_test_util.hpp"

namespace gf::dem::test {
namespace {

using Triangle3 = std::array<Vec3, 3>;
const std::filesystem::path kDir = std::filesystem::temp_directory_path() / "grainflow_dem_mesh_test";

void writeAsciiStl(const std::filesystem::path& path, const std::vector<Triangle3>& triangles) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid mesh\n";
  for (const Triangle3& t : triangles) {
    out << " facet normal 0 0 1\n  outer loop\n";
    for (const Vec3& v : t) out << "   vertex " << v.x << " " << v.y << " " << v.z << "\n";
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid mesh\n";
}

struct Resting {
  Vec3 position;
  long long wallContacts;
  double verticalWallForce;
  double weight;
};

constexpr double kRadius = 0.001, kYoungs = 1e7, kPoisson = 0.3;

/// Drops a sphere (r = 1 mm) from rest, just touching, at `start` onto the mesh and lets it settle.
Resting restOn(const std::vector<Triangle3>& mesh, const std::string& name, const Vec3& start,
               double friction = 0.5) {
  std::filesystem::create_directories(kDir);
  writeAsciiStl(kDir / (name + ".stl"), mesh);
  const std::string yaml = materialsYaml("hertz_mindlin", 0.3, friction, kYoungs, kPoisson) + fmt::format(R"(
domain: {{min: [-0.02, -0.02, -0.02], max: [0.02, 0.02, 0.02]}}
walls:
  - {{type: stl, file: {}.stl}}
insertion:
  - {{type: csv_file, file: {}.csv}}
)",
                                                                                                    name, name);
  {
    std::ofstream csv(kDir / (name + ".csv"));
    csv.precision(17);
    csv << "x,y,z,r\n" << start.x << "," << start.y << "," << start.z << "," << kRadius << "\n";
  }
  Params params = Params::loadString(yaml, (kDir / (name + ".yaml")).string());
  const Domain domain = Domain::read(params);
  System s(params, domain, {0, 0, -9.81});
  for (int k = 0; k < 40000; ++k) s.step(1e-6);
  Resting r;
  r.position = s.particles().position[0];
  r.wallContacts = s.contactStatistics().wallContacts;
  r.verticalWallForce = 0.0;
  for (const WallLoad& l : s.wallLoads()) r.verticalWallForce -= l.force.z;
  r.weight = 9.81 * s.particles().mass[0];
  return r;
}

/// Overlap of a sphere resting on a rigid flat (Hertz, see the file comment).
double restingOverlap() {
  const double mass = 2500.0 * 4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3);
  const double effectiveYoungs = kYoungs / (1.0 - kPoisson * kPoisson);
  return std::pow(mass * 9.81 / (4.0 / 3.0 * effectiveYoungs * std::sqrt(kRadius)), 2.0 / 3.0);
}

}  // namespace

TEST(DemMeshContact, SphereOnSharedEdgeGetsOneContact) {
  // Square [-L, L]^2 at z = 0 as two triangles sharing the diagonal; the sphere sits on the diagonal.
  const double L = 0.01;
  const std::vector<Triangle3> square{Triangle3{Vec3{-L, -L, 0}, Vec3{L, -L, 0}, Vec3{L, L, 0}},
                                      Triangle3{Vec3{-L, -L, 0}, Vec3{L, L, 0}, Vec3{-L, L, 0}}};
  const Resting r = restOn(square, "edge", {0.002, 0.002, kRadius});
  EXPECT_EQ(r.wallContacts, 1);
  EXPECT_NEAR(kRadius - r.position.z, restingOverlap(), 0.01 * restingOverlap());  // two contacts: -37 %
  EXPECT_NEAR(r.verticalWallForce, r.weight, 1e-3 * r.weight);
}

TEST(DemMeshContact, SphereOnSharedVertexGetsOneContact) {
  // Hexagon of six triangles around the vertex at the origin; the sphere sits on that vertex.
  std::vector<Triangle3> fan;
  const double R = 0.01;
  for (int k = 0; k < 6; ++k) {
    const double a0 = k * std::numbers::pi / 3.0, a1 = (k + 1) * std::numbers::pi / 3.0;
    fan.push_back({Vec3{0, 0, 0}, Vec3{R * std::cos(a0), R * std::sin(a0), 0}, Vec3{R * std::cos(a1), R * std::sin(a1), 0}});
  }
  const Resting r = restOn(fan, "vertex", {0, 0, kRadius});
  EXPECT_EQ(r.wallContacts, 1);
  EXPECT_NEAR(kRadius - r.position.z, restingOverlap(), 0.01 * restingOverlap());
  EXPECT_NEAR(r.verticalWallForce, r.weight, 1e-3 * r.weight);
}

TEST(DemMeshContact, SphereInConcaveGrooveKeepsBothFaceContacts) {
  // 90-degree groove along x: faces z = |y|, each as two triangles; the sphere rests on both faces.
  const double L = 0.01;
  const std::vector<Triangle3> groove{Triangle3{Vec3{-L, 0, 0}, Vec3{L, 0, 0}, Vec3{L, L, L}},
                                      Triangle3{Vec3{-L, 0, 0}, Vec3{L, L, L}, Vec3{-L, L, L}},
                                      Triangle3{Vec3{-L, 0, 0}, Vec3{L, -L, L}, Vec3{L, 0, 0}},
                                      Triangle3{Vec3{-L, 0, 0}, Vec3{-L, -L, L}, Vec3{L, -L, L}}};
  // Frictionless, so that the faces carry the weight by normal forces only.
  const Resting r = restOn(groove, "groove", {0.001, 0, kRadius * std::sqrt(2.0)}, 0.0);
  EXPECT_EQ(r.wallContacts, 2);
  EXPECT_NEAR(r.verticalWallForce, r.weight, 1e-3 * r.weight);
  // Each face carries m g / sqrt(2) along its normal: overlap from Hertz with that load.
  const double overlap = restingOverlap() * std::pow(1.0 / std::sqrt(2.0), 2.0 / 3.0);
  EXPECT_NEAR(kRadius * std::sqrt(2.0) - r.position.z, std::sqrt(2.0) * overlap, 0.02 * std::sqrt(2.0) * overlap);
}

// Wall contact lists of a mesh of many triangles (binned, TriangleBins in wall_contact_list.cpp)
// hold the entries a test of every primitive by every particle gives, in the same order: a
// wavy floor of 3200 triangles, a plane beside it, spheres of two sizes above, below and around
// the mesh (some outside its bounds).
TEST(DemMeshContact, BinnedMeshWallListEqualsTestingEveryTriangle) {
  std::vector<WallPrimitive> primitives;
  const int cells = 40;
  const double size = 0.04, h = size / cells;
  auto floor = [&](int i, int j) {
    const double x = i * h, y = j * h;
    return Vec3{x, y, 0.004 + 0.002 * std::sin(300.0 * x) * std::cos(200.0 * y)};
  };
  WallPrimitive plane;
  plane.kind = PrimitiveKind::Plane;
  plane.a = {0.02, 0, 0};
  plane.b = {-1, 0, 0};  // x = 0.02, facing -x (mid-mesh: entries from both lists interleave)
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      if (i == cells / 2 && j == cells / 2) primitives.push_back(plane);
      WallPrimitive t;
      t.kind = PrimitiveKind::Triangle;
      t.a = floor(i, j), t.b = floor(i + 1, j), t.c = floor(i + 1, j + 1);
      primitives.push_back(t);
      t.b = floor(i + 1, j + 1), t.c = floor(i, j + 1);
      primitives.push_back(t);
    }
  ParticleSet p;
  Random rng(4);
  for (int k = 0; k < 4000; ++k)
    p.add(k, 0, k % 2 ? 0.0005 : 0.001, 2500,
          {rng.uniform(-0.005, 0.045), rng.uniform(-0.005, 0.045), rng.uniform(0.0, 0.01)});
  const double skin = 0.0002;
  WallContactList list;
  list.build(p, primitives, skin, {}, false);
  std::vector<std::uint32_t> expectedStart{0}, expected;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::uint32_t w = 0; w < primitives.size(); ++w) {
      const WallPrimitive& prim = primitives[w];
      const double d = prim.kind == PrimitiveKind::Plane ? dot(p.position[i] - prim.a, prim.b)
                                                         : distanceToPrimitive(prim, p.position[i]).distance;
      if (d < p.radius[i] + skin) expected.push_back(w);
    }
    expectedStart.push_back(static_cast<std::uint32_t>(expected.size()));
  }
  EXPECT_EQ(list.rowStart, expectedStart);
  EXPECT_EQ(list.primitive, expected);
  EXPECT_GT(expected.size(), 4000u);  // spheres near the floor touch several triangles
}

}  // namespace gf::dem::test
