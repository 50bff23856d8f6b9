// Wall geometry and motion: STL meshes, cylinders (inside/outside), cones, moving and rotating
// walls, wall loads. (Reading STL files is tested in tests/io/stl_reader_test.cpp.)
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "dem/walls/wall_primitive.hpp"
#include "../io/stl_test_writer.hpp"
#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

using test::DemCase;
using test::materialsYaml;

const std::filesystem::path kTmp = std::filesystem::temp_directory_path() / "grainflow_dem_walls_test";

TEST(DemWalls, DistanceToPrimitivesIsExact) {
  WallPrimitive tri;
  tri.kind = PrimitiveKind::Triangle;
  tri.a = {0, 0, 0};
  tri.b = {1, 0, 0};
  tri.c = {0, 1, 0};
  EXPECT_DOUBLE_EQ(distanceToPrimitive(tri, {0.2, 0.2, 0.5}).distance, 0.5);  // face
  EXPECT_DOUBLE_EQ(distanceToPrimitive(tri, {2, 0, 0}).distance, 1.0);        // vertex b
  EXPECT_NEAR(distanceToPrimitive(tri, {1, 1, 0}).distance, std::sqrt(0.5), 1e-15);  // edge bc
  WallPrimitive cone;
  cone.kind = PrimitiveKind::Axisymmetric;
  cone.a = {0, 0, 0};
  cone.b = {0, 0, 1};
  cone.r0 = 0.0;
  cone.r1 = 1.0;
  cone.length = 1.0;  // 45 degree cone
  const WallDistance d = distanceToPrimitive(cone, {0, 0, 0.5});  // on the axis
  EXPECT_NEAR(d.distance, 0.5 / std::sqrt(2.0), 1e-12);
  const WallDistance out = distanceToPrimitive(cone, {1, 0, 0.5});  // outside
  EXPECT_NEAR(out.distance, 0.5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(out.normal.x, 1 / std::sqrt(2.0), 1e-12);
}

double bounceOn(const std::string& walls, const Vec3& start, const Vec3& v, Vec3* after = nullptr) {
  std::filesystem::create_directories(kTmp);
  const std::string yaml = materialsYaml("hertz_mindlin", 0.8, 0.0) +
                           "domain: {min: [-0.05, -0.05, -0.05], max: [0.05, 0.05, 0.05]}\nwalls:\n" + walls;
  Params params = Params::loadString(yaml, (kTmp / "case.yaml").string());
  const Domain domain = Domain::read(params);
  System s(params, domain, {0, 0, 0});
  s.particles().add(0, 0, 0.001, 2500, start, v);
  s.refresh();
  const double speed = norm(v);
  for (int k = 0; k < 20000; ++k) s.step(2e-7);
  if (after) *after = s.particles().velocity[0];
  return dot(s.particles().velocity[0], v) / (-speed * speed);
}

TEST(DemWalls, StlPlaneCylinderAndConeReflectWithRestitution) {
  gf::testing::writeStl(kTmp / "square.stl", gf::testing::squareTriangles(0.02), true);
  const double mesh = bounceOn("  - {type: stl, file: square.stl}\n", {0.001, 0.002, 0.0012}, {0, 0, -0.5});
  EXPECT_NEAR(mesh, 0.8, 0.01 * 0.8);
  // Inside a cylinder of radius 0.01 (drum), moving radially outwards.
  const double inner = bounceOn("  - {type: cylinder, base: [0, 0, -0.01], axis: [0, 0, 0.02], radius: 0.01}\n",
                                {0.0088, 0, 0}, {0.5, 0, 0});
  EXPECT_NEAR(inner, 0.8, 0.01 * 0.8);
  // Outside the same cylinder (obstacle), moving radially inwards.
  const double outer = bounceOn("  - {type: cylinder, base: [0, 0, -0.01], axis: [0, 0, 0.02], radius: 0.01}\n",
                                {0.0112, 0, 0}, {-0.5, 0, 0});
  EXPECT_NEAR(outer, 0.8, 0.01 * 0.8);
  // Inside a 45-degree cone, hitting the mantle along its normal.
  Vec3 after;
  const double r = 0.01, z = 0.01;  // point on the mantle: rho = z
  const Vec3 n = Vec3{-1, 0, 1} / std::sqrt(2.0);  // inward normal at (r, 0, z)
  const Vec3 start = Vec3{r, 0, z} + 0.00101 * n;
  const double cone = bounceOn("  - {type: cone, base: [0, 0, 0], axis: [0, 0, 0.03], radius_base: 0, radius_top: 0.03}\n",
                               start, -0.5 * n, &after);
  EXPECT_NEAR(cone, 0.8, 0.01 * 0.8);
}

// A piston (plane) moving at V into an elastic particle at rest: after the collision the particle
// moves at 2V (elastic reflection in the wall frame).
TEST(DemWalls, MovingPistonReflectsInWallFrame) {
  const std::string yaml = materialsYaml("hertz_mindlin", 1.0, 0.0) + R"(
domain: {min: [-0.05, -0.05, -0.05], max: [0.05, 0.05, 0.05]}
walls:
  - {type: plane, name: piston, point: [0, 0, 0], normal: [0, 0, 1], velocity: [0, 0, 0.2]}
)";
  DemCase c(yaml, {0, 0, 0});
  c->particles().add(0, 0, 0.001, 2500, {0, 0, 0.0011});
  c->refresh();
  double peakForce = 0.0;
  for (int k = 0; k < 20000; ++k) {
    c->step(2e-7);
    peakForce = std::max(peakForce, -c->wallLoads()[0].force.z);
  }
  EXPECT_NEAR(c->particles().velocity[0].z, 0.4, 0.004);
  EXPECT_GT(peakForce, 0.0);  // the wall load sees the particle pushing back
  EXPECT_EQ(c->wallLoads()[0].name, "piston");
}

// A particle resting on the inside of a drum spinning about its own axis (no gravity, held by
// a small radial push) is dragged along by friction towards the wall velocity.
TEST(DemWalls, RotatingDrumDragsParticleByFriction) {
  const std::string yaml = materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [-0.05, -0.05, -0.05], max: [0.05, 0.05, 0.05]}
walls:
  - {type: cylinder, name: drum, base: [0, 0, -0.02], axis: [0, 0, 0.04], radius: 0.02,
     angular_velocity: [0, 0, 5], centre: [0, 0, 0]}
)";
  DemCase c(yaml, {0.5, 0, 0});  // "gravity" pushes it onto the wall at x = +R
  c->particles().add(0, 0, 0.001, 2500, {0.019, 0, 0});
  c->refresh();
  for (int k = 0; k < 20000; ++k) c->step(5e-6);
  EXPECT_GT(c->particles().velocity[0].y, 0.0);  // wall surface moves along +y at x = +R
  EXPECT_LT(c->wallLoads()[0].torque.z, 0.0);  // the particle brakes the drum
}

}  // namespace
}  // namespace gf::dem

namespace gf::dem {
namespace {

// A bed settled on a floor in a box periodic in x and y: the floor (wall load) carries the whole
// weight once the bed is at rest (no side walls, so no Janssen wall friction).
TEST(DemWalls, SettledPeriodicBedFloorCarriesItsWeight) {
  const std::string yaml = test::materialsYaml("hertz_mindlin", 0.3, 0.5) + R"(
domain: {min: [0, 0, 0], max: [0.012, 0.012, 0.04], periodic: [1, 1, 0]}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1]}
insertion:
  - {type: random_packing, min: [0, 0, 0.0], max: [0.012, 0.012, 0.035], count: 300, seed: 6,
     size: {distribution: rosin_rammler, characteristic_diameter: 0.002, spread: 5, min_diameter: 0.0016,
            max_diameter: 0.0024}}
)";
  test::DemCase c(yaml, {0, 0, -9.81});
  double weight = 0.0;
  for (double m : c->particles().mass) weight += 9.81 * m;
  for (int k = 0; k < 30000; ++k) c->step(1e-5);
  const double floorForce = -c->wallLoads()[0].force.z;
  EXPECT_NEAR(floorForce, weight, 0.02 * weight);
  EXPECT_LT(c->energy().translational, 1e-4 * weight * 0.001);  // at rest: KE << m g d
  EXPECT_GT(c->contactStatistics().coordinationNumber, 3.5);   // packed (isostatic ~4-6)
  EXPECT_NO_THROW(c->checkHealth(30000, 0.3));
}

}  // namespace
}  // namespace gf::dem
