// Checkpoint/restart is bit-identical; checkHealth names place and quantity of a blow-up.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

const std::string kCavity = R"(
domain: {min: [0, 0, 0], max: [1, 1, 0.1]}
fluid:
  density: 1
  viscosity: 0.01
  cells: [24, 24, 1]
  scalar: {enabled: true, diffusivity: 0.001}
  boundaries:
    y_max: {type: wall, velocity: [1, 0, 0], scalar: fixed, scalar_value: 1}
)";

TEST(Restart, BitIdentical) {
  auto a = test::makeCase(kCavity);
  for (int n = 0; n < 10; ++n) a.solver->step(0.02);
  BinaryWriter w;
  a.solver->save(w);
  for (int n = 0; n < 10; ++n) a.solver->step(n % 2 ? 0.02 : 0.015);  // variable dt too
  auto b = test::makeCase(kCavity);
  BinaryReader r(w.bytes().data(), w.bytes().size());
  b.solver->load(r);
  EXPECT_TRUE(r.atEnd());
  for (int n = 0; n < 10; ++n) b.solver->step(n % 2 ? 0.02 : 0.015);
  for (int c = 0; c < 2; ++c) EXPECT_EQ(a.solver->velocity(c).data(), b.solver->velocity(c).data());
  EXPECT_EQ(a.solver->pressure().data(), b.solver->pressure().data());
  EXPECT_EQ(a.solver->scalar().data(), b.solver->scalar().data());
  EXPECT_EQ(a.solver->time(), b.solver->time());
}

TEST(Restart, WrongGridIsRejected) {
  auto a = test::makeCase(kCavity);
  BinaryWriter w;
  a.solver->save(w);
  std::string other = kCavity;
  other.replace(other.find("[24, 24, 1]"), 11, "[16, 16, 1]");
  auto b = test::makeCase(other);
  BinaryReader r(w.bytes().data(), w.bytes().size());
  EXPECT_THROW(b.solver->load(r), CheckpointError);
}

TEST(Health, NaNIsReportedWithCellAndQuantity) {
  auto a = test::makeCase(kCavity);
  a.solver->setVelocity([](const Vec3& x) {
    return Vec3{(x.x > 0.5 && x.x < 0.55 && x.y > 0.3 && x.y < 0.35) ? std::numeric_limits<double>::quiet_NaN() : 0.0,
                0.0, 0.0};
  });
  try {
    a.solver->checkHealth(7, 0.1);
    FAIL() << "no DivergenceError";
  } catch (const DivergenceError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("velocity_x"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(13, 7, 0)"), std::string::npos) << msg;
    EXPECT_EQ(e.step(), 7);
  }
}

TEST(Health, CflAboveLimitIsReported) {
  auto a = test::makeCase("domain: {min: [0, 0, 0], max: [1, 1, 0.1], periodic: [1, 1, 0]}\n"
                          "fluid: {cells: [8, 8, 1], cfl: 0.5, cfl_limit: 1.0}\n");
  a.solver->setVelocity([](const Vec3&) { return Vec3{1.0, 0.0, 0.0}; });
  EXPECT_NEAR(a.solver->stableTimeStep(), 0.5 / 8, 1e-12);
  a.solver->step(0.5);  // CFL 4
  EXPECT_THROW(a.solver->checkHealth(1, 0.5), DivergenceError);
}

}  // namespace
}  // namespace gf::fluid

namespace gf::fluid {
namespace {

TEST(Restart, SameThreadCountIsBitIdentical3D) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [1, 1, 1]}
fluid:
  density: 1
  viscosity: 0.01
  cells: [48, 48, 48]
  boundaries:
    y_max: {type: wall, velocity: [1, 0, 0]}
)";
  auto a = test::makeCase(yaml);
  auto b = test::makeCase(yaml);
  for (int n = 0; n < 2; ++n) {  // 48^2 lines: the threaded loop paths are taken
    a.solver->step(0.01);
    b.solver->step(0.01);
  }
  for (int c = 0; c < 3; ++c) EXPECT_EQ(a.solver->velocity(c).data(), b.solver->velocity(c).data());
  EXPECT_EQ(a.solver->pressure().data(), b.solver->pressure().data());
}

}  // namespace
}  // namespace gf::fluid
