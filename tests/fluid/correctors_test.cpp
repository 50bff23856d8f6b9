// PISO-style pressure correctors (fluid.correctors). The projection corrects the
// velocity with the time (and drag) diagonal only, so u^{n+1}, p^{n+1} leave a momentum residual:
// the implicit viscous operator applied to the correction (splitting error). Each further
// corrector (momentum residual with the new pressure, Jacobi update, projection) must shrink it,
// keep the velocity discretely divergence-free, and keep the Taylor-Green vortex
// (Taylor & Green 1937: u = sin x cos y e^{-2 nu t}) at least as accurate, at a large time step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct TgRun {
  double error, residual, divergence;
};

TgRun taylorGreen(int correctors, int steps) {
  const std::string L = std::to_string(2.0 * kPi);
  auto c = test::makeCase("domain: {min: [0, 0, 0], max: [" + L + ", " + L +
                          ", 1], periodic: [1, 1, 1]}\n"
                          "fluid:\n  density: 1.0\n  viscosity: 0.1\n  convection: central\n  cells: [32, 32, 1]\n"
                          "  pressure: {tolerance: 1e-12}\n  momentum_tolerance: 1e-13\n  correctors: " +
                          std::to_string(correctors) + "\n");
  Solver& s = *c.solver;
  s.setVelocity([](const Vec3& x) { return Vec3{std::sin(x.x) * std::cos(x.y), -std::cos(x.x) * std::sin(x.y), 0.0}; });
  s.setPressure([](const Vec3& x) { return 0.25 * (std::cos(2 * x.x) + std::cos(2 * x.y)); });
  const double T = 1.0;
  for (int i = 0; i < steps; ++i) s.step(T / steps);
  const double decay = std::exp(-2.0 * 0.1 * T);
  const double e = std::max(
      test::maxFaceError(s, 0, [&](const Vec3& x) { return std::sin(x.x) * std::cos(x.y) * decay; }),
      test::maxFaceError(s, 1, [&](const Vec3& x) { return -std::cos(x.x) * std::sin(x.y) * decay; }));
  return {e, s.lastStep().momentumResidual, s.maxDivergence()};
}

TEST(Correctors, ShrinkTheSplittingResidualAndKeepTaylorGreenAccuracy) {
  const int steps = 5;  // dt = 0.2: CFL 1, mu dt / h^2 = 0.5
  const TgRun one = taylorGreen(1, steps), two = taylorGreen(2, steps), four = taylorGreen(4, steps);
  std::printf("TG2D dt=0.2: error 1 corrector %.4e, 2: %.4e, 4: %.4e; residual entering corrector 2: %.3e, 4: %.3e\n",
              one.error, two.error, four.error, two.residual, four.residual);
  EXPECT_EQ(one.residual, 0.0);
  EXPECT_GT(two.residual, 0.0);
  EXPECT_LT(four.residual, 0.1 * two.residual);
  EXPECT_LT(two.divergence, 1e-9);
  EXPECT_LT(four.divergence, 1e-9);
  EXPECT_LE(four.error, 1.02 * one.error);
}

}  // namespace
}  // namespace gf::fluid
