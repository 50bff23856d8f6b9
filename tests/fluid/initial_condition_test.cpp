// fluid.initial: uniform (default) and taylor_green fields (src/fluid/initial_condition.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fluid/initial_condition.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

TEST(InitialCondition, TaylorGreenOnTheStaggeredFaces) {
  // Wavelength 2 m in a 2 m box, U0 = 0.5 m/s, rho = 3 kg/m^3, plus a uniform 0.1 m/s along x.
  auto c = test::makeCase(
      "domain: {min: [0, 0, 0], max: [2, 2, 1], periodic: [1, 1, 1]}\n"
      "fluid:\n  density: 3.0\n  cells: [8, 8, 1]\n"
      "  initial: {type: taylor_green, amplitude: 0.5, wavelength: 2.0, velocity: [0.1, 0, 0], pressure: 7.0}\n");
  const double k = std::numbers::pi;
  const double errU = test::maxFaceError(*c.solver, 0, [&](const Vec3& x) { return 0.1 + 0.5 * std::sin(k * x.x) * std::cos(k * x.y); });
  const double errV = test::maxFaceError(*c.solver, 1, [&](const Vec3& x) { return -0.5 * std::cos(k * x.x) * std::sin(k * x.y); });
  EXPECT_LT(errU, 1e-14);
  EXPECT_LT(errV, 1e-14);
  const Vec3 centre = c.solver->grid().cellCentre(2, 5, 0);
  EXPECT_NEAR(c.solver->pressure()(2, 5, 0), 7.0 + 0.25 * 3.0 * 0.25 * (std::cos(2 * k * centre.x) + std::cos(2 * k * centre.y)), 1e-14);
}

TEST(InitialCondition, UniformIsTheDefault) {
  auto c = test::makeCase("domain: {min: [0, 0, 0], max: [1, 1, 1], periodic: [1, 1, 1]}\nfluid:\n  cells: [4, 4, 4]\n  initial: {velocity: [0, 0, 0.2]}\n");
  EXPECT_LT(test::maxFaceError(*c.solver, 2, [](const Vec3&) { return 0.2; }), 1e-15);
  EXPECT_LT(test::maxFaceError(*c.solver, 0, [](const Vec3&) { return 0.0; }), 1e-15);
}

}  // namespace
}  // namespace gf::fluid
