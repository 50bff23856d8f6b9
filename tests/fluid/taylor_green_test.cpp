// Taylor-Green vortex. 2D: exact decaying solution u = sin x cos y e^{-2 nu t},
// v = -cos x sin y e^{-2 nu t}, p = rho/4 (cos 2x + cos 2y) e^{-4 nu t} (Taylor & Green 1937).
// Observed orders from three resolutions must be >= 1.9:
//  - space and time together (dt proportional to h) against the exact solution,
//  - time alone by Richardson differences on one grid (spatial error cancels).
// 3D (low Re): kinetic-energy Richardson order over three grids at fixed dt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string tgCase(int n, int nz, const std::string& scheme) {
  const std::string L = std::to_string(2.0 * kPi);
  return "domain: {min: [0, 0, 0], max: [" + L + ", " + L + ", " + (nz == 1 ? std::string("1") : L) +
         "], periodic: [1, 1, 1]}\n"
         "fluid:\n  density: 1.0\n  viscosity: 0.05\n  convection: " + scheme +
         "\n  cells: [" + std::to_string(n) + ", " + std::to_string(n) + ", " + std::to_string(nz) +
         "]\n  pressure: {tolerance: 1e-12}\n  momentum_tolerance: 1e-13\n";
}

void initialise2D(Solver& s) {
  s.setVelocity([](const Vec3& x) { return Vec3{std::sin(x.x) * std::cos(x.y), -std::cos(x.x) * std::sin(x.y), 0.0}; });
  s.setPressure([](const Vec3& x) { return 0.25 * (std::cos(2 * x.x) + std::cos(2 * x.y)); });
}

double runError2D(int n, int steps, double T, const std::string& scheme) {
  auto c = test::makeCase(tgCase(n, 1, scheme));
  Solver& s = *c.solver;
  initialise2D(s);
  for (int i = 0; i < steps; ++i) s.step(T / steps);
  const double decay = std::exp(-2.0 * 0.05 * T);
  return std::max(test::maxFaceError(s, 0, [&](const Vec3& x) { return std::sin(x.x) * std::cos(x.y) * decay; }),
                  test::maxFaceError(s, 1, [&](const Vec3& x) { return -std::cos(x.x) * std::sin(x.y) * decay; }));
}

TEST(TaylorGreen, SpaceTimeOrder2DCentral) {
  const double T = 1.0;
  const double e1 = runError2D(16, 8, T, "central");
  const double e2 = runError2D(32, 16, T, "central");
  const double e3 = runError2D(64, 32, T, "central");
  const double p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e3);
  std::printf("TG2D central space+time: errors %.3e %.3e %.3e, orders %.3f %.3f\n", e1, e2, e3, p1, p2);
  EXPECT_GE(p1, 1.9) << e1 << " " << e2 << " " << e3;
  EXPECT_GE(p2, 1.9) << e1 << " " << e2 << " " << e3;
  EXPECT_LT(e3, 2e-3);
}

TEST(TaylorGreen, VanLeerConvergesAndDecays) {
  const double e2 = runError2D(32, 16, 1.0, "van_leer");
  const double e3 = runError2D(64, 32, 1.0, "van_leer");
  std::printf("TG2D van Leer: errors %.3e %.3e, order %.3f\n", e2, e3, std::log2(e2 / e3));
  EXPECT_GE(std::log2(e2 / e3), 1.5) << e2 << " " << e3;  // limiter clips extrema: order slightly below 2
  EXPECT_LT(e3, 5e-3);
}

TEST(TaylorGreen, TimeOrder2DRichardson) {
  const double T = 1.0;
  std::vector<std::vector<double>> u;
  for (int steps : {4, 8, 16}) {
    auto c = test::makeCase(tgCase(32, 1, "central"));
    Solver& s = *c.solver;
    initialise2D(s);
    for (int i = 0; i < steps; ++i) s.step(T / steps);
    u.push_back(s.velocity(0).data());
  }
  double d1 = 0.0, d2 = 0.0;
  for (std::size_t i = 0; i < u[0].size(); ++i) {
    d1 = std::max(d1, std::abs(u[0][i] - u[1][i]));
    d2 = std::max(d2, std::abs(u[1][i] - u[2][i]));
  }
  std::printf("TG2D time order (Richardson): %.3f\n", std::log2(d1 / d2));
  EXPECT_GE(std::log2(d1 / d2), 1.9) << d1 << " " << d2;
}

double kineticEnergy3D(int n) {
  auto c = test::makeCase(tgCase(n, n, "central"));
  Solver& s = *c.solver;
  s.setVelocity([](const Vec3& x) {
    return Vec3{std::sin(x.x) * std::cos(x.y) * std::cos(x.z), -std::cos(x.x) * std::sin(x.y) * std::cos(x.z), 0.0};
  });
  for (int i = 0; i < 10; ++i) s.step(0.05);
  double e = 0.0;
  for (int comp = 0; comp < 3; ++comp) {
    const Field& u = s.velocity(comp);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) e += 0.5 * u(i, j, k) * u(i, j, k);
  }
  return e * s.grid().cellVolume();
}

TEST(TaylorGreen, SpaceOrder3DLowRe) {
  const double e8 = kineticEnergy3D(8), e16 = kineticEnergy3D(16), e32 = kineticEnergy3D(32);
  // Low Re: energy decays close to the Stokes rate exp(-6 nu t) from E0 = pi^3 ... (2pi)^3/8.
  const double E0 = std::pow(2 * kPi, 3) / 8.0;
  EXPECT_NEAR(e32 / E0, std::exp(-6.0 * 0.05 * 0.5), 0.01);
  std::printf("TG3D kinetic-energy space order: %.3f\n", std::log2((e8 - e16) / (e16 - e32)));
  EXPECT_GE(std::log2((e8 - e16) / (e16 - e32)), 1.9) << e8 << " " << e16 << " " << e32;
}

}  // namespace
}  // namespace gf::fluid
