// Passive scalar.
//  - A step advected by a uniform flow with the van Leer TVD scheme stays in [0, 1] (TVD
//    property, Harten 1983), while central differencing over/undershoots (so the test can fail).
//  - Diffusion of a periodic sine mode decays as exp(-D k^2 t) (analytic), second order.
//  - Fixed values on two walls and no flow: the steady profile is linear (exact).
#include <gtest/gtest.h>

#include <cmath>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string periodicCase(const std::string& scheme, double diffusivity, int n) {
  return "domain: {min: [0, 0, 0], max: [1, 0.25, 0.1], periodic: [1, 1, 0]}\n"
         "fluid:\n  density: 1\n  viscosity: 0\n  convection: " + scheme + "\n  cells: [" + std::to_string(n) +
         ", 4, 1]\n  scalar: {enabled: true, diffusivity: " + std::to_string(diffusivity) + "}\n";
}

std::pair<double, double> stepRange(const std::string& scheme) {
  auto c = test::makeCase(periodicCase(scheme, 0.0, 100));
  Solver& s = *c.solver;
  s.setVelocity([](const Vec3&) { return Vec3{1.0, 0.0, 0.0}; });
  s.setScalar([](const Vec3& x) { return (x.x > 0.2 && x.x < 0.5) ? 1.0 : 0.0; });
  double lo = 0.0, hi = 1.0;
  for (int n = 0; n < 100; ++n) {
    s.step(0.004);  // CFL 0.4
    for (int i = 0; i < 100; ++i) {
      lo = std::min(lo, s.scalar()(i, 1, 0));
      hi = std::max(hi, s.scalar()(i, 1, 0));
    }
  }
  return {lo, hi};
}

TEST(Scalar, VanLeerStepStaysBounded) {
  const auto [lo, hi] = stepRange("van_leer");
  EXPECT_GE(lo, -1e-12);
  EXPECT_LE(hi, 1.0 + 1e-12);
}

TEST(Scalar, CentralStepOvershoots) {
  const auto [lo, hi] = stepRange("central");
  EXPECT_TRUE(lo < -1e-3 || hi > 1.0 + 1e-3);
}

double diffusionError(int n) {
  const double D = 0.01, T = 1.0;
  auto c = test::makeCase(periodicCase("van_leer", D, n));
  Solver& s = *c.solver;
  s.setScalar([](const Vec3& x) { return std::sin(2 * kPi * x.x); });
  for (int i = 0; i < 10; ++i) s.step(T / 10);
  const double decay = std::exp(-D * 4 * kPi * kPi * T);
  double e = 0.0;
  for (int i = 0; i < n; ++i)
    e = std::max(e, std::abs(s.scalar()(i, 2, 0) - decay * std::sin(2 * kPi * (i + 0.5) / n)));
  return e;
}

TEST(Scalar, DiffusionMatchesAnalyticDecay) {
  const double e1 = diffusionError(32), e2 = diffusionError(64);
  EXPECT_LT(e2, 3e-4);  // leading error D k^2 T (k h)^2 / 12 * amplitude = 2.1e-4
  EXPECT_GE(std::log2(e1 / e2), 1.8) << e1 << " " << e2;
}

TEST(Scalar, FixedWallsGiveLinearProfile) {
  auto c = test::makeCase(R"(
domain: {min: [0, 0, 0], max: [0.25, 1, 0.1], periodic: [1, 0, 0]}
fluid:
  density: 1
  viscosity: 0.001
  cells: [4, 20, 1]
  scalar: {enabled: true, diffusivity: 0.05}
  boundaries:
    y_min: {type: wall, scalar: fixed, scalar_value: 2.0}
    y_max: {type: wall, scalar: fixed, scalar_value: -1.0}
)");
  Solver& s = *c.solver;
  for (int i = 0; i < 400; ++i) s.step(0.1);
  for (int j = 0; j < 20; ++j) EXPECT_NEAR(s.scalar()(1, j, 0), 2.0 - 3.0 * (j + 0.5) / 20.0, 1e-8);
}

TEST(Scalar, UniformSourceGrowsLinearly) {
  auto d = test::makeCase("domain: {min: [0, 0, 0], max: [1, 1, 0.1], periodic: [1, 1, 0]}\n"
                          "fluid: {cells: [4, 4, 1], scalar: {enabled: true, source: 0.5}}\n");
  for (int i = 0; i < 10; ++i) d.solver->step(0.2);
  EXPECT_NEAR(d.solver->scalar()(2, 2, 0), 0.5 * 2.0, 1e-12);
}

}  // namespace
}  // namespace gf::fluid
