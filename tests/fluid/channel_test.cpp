// Plane Poiseuille flow: periodic channel between no-slip walls.
//  - imposed mean pressure gradient G: u(y) = G y (H - y) / (2 mu)  (exact for the MAC scheme with
//    the quadratic wall closure, so compared within 1e-6 relative);
//  - imposed bulk velocity U: the controller must find G = 12 mu U / H^2 (White, Viscous Fluid
//    Flow, 3rd ed., eq. 3-42), up to the midpoint-rule h^2 term of the discrete flow rate.
#include <gtest/gtest.h>

#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

std::string channelCase(const std::string& driving, int ny, const std::string& model = "A") {
  return R"(
domain: {min: [0, 0, 0], max: [0.5, 1, 0.1], periodic: [1, 0, 0]}
fluid:
  density: 2.0
  viscosity: 0.5
  model: )" + model + R"(
  cells: [8, )" + std::to_string(ny) + R"(, 1]
  pressure: {tolerance: 1e-12}
  momentum_tolerance: 1e-13
  driving: )" + driving + R"(
)";
}

TEST(Channel, PoiseuilleWithImposedGradientIsExact) {
  auto c = test::makeCase(channelCase("{mode: pressure_gradient, axis: x, pressure_gradient: 3.0}", 16));
  Solver& s = *c.solver;
  const double G = 3.0, mu = 0.5, H = 1.0, rho = 2.0;
  const double tau = rho * H * H / mu;  // viscous time
  for (int n = 0; n < 300; ++n) s.step(0.05 * tau);
  const double umax = G * H * H / (8.0 * mu);
  const double err = test::maxFaceError(s, 0, [&](const Vec3& x) { return G * x.y * (H - x.y) / (2.0 * mu); });
  EXPECT_LT(err / umax, 1e-6) << "max error " << err;
  EXPECT_LT(test::maxFaceError(s, 1, [](const Vec3&) { return 0.0; }), 1e-12);
}

TEST(Channel, ImposedFlowRateGivesAnalyticGradient) {
  const double U = 0.3, mu = 0.5, H = 1.0, rho = 2.0;
  auto c = test::makeCase(channelCase("{mode: flow_rate, axis: x, bulk_velocity: 0.3}", 16, "B"));
  Solver& s = *c.solver;
  const double tau = rho * H * H / mu;
  for (int n = 0; n < 300; ++n) s.step(0.05 * tau);
  // The controller imposes the discrete bulk velocity (midpoint sum over the cells), which for
  // the exact parabola is G/(2 mu) (H^2/6 + h^2/12): G = 12 mu U / (H^2 + h^2/2), -> analytic as h -> 0.
  const double h = H / 16;
  const double expected = 12.0 * mu * U / (H * H + 0.5 * h * h);
  EXPECT_NEAR(s.drivingPressureGradient(), expected, 1e-6 * expected);
  const double analytic = 12.0 * mu * U / (H * H);
  EXPECT_NEAR(s.drivingPressureGradient(), analytic, 3e-3 * analytic);
}

}  // namespace
}  // namespace gf::fluid

namespace gf::fluid {
namespace {

// The driving gradient is a body force in the momentum equation, but it is part of grad p for
// whoever asks for the pressure gradient (the coupling's -V_p grad p force): with an imposed
// -dp/dx = G the cell-centred gradient is -G everywhere (the periodic part is zero in Poiseuille flow).
TEST(Channel, PressureGradientIncludesTheDrivingGradient) {
  auto c = test::makeCase(channelCase("{mode: pressure_gradient, axis: x, pressure_gradient: 3.0}", 8));
  Solver& s = *c.solver;
  for (int n = 0; n < 20; ++n) s.step(0.05);
  Field gp[3];
  s.pressureGradient(gp);
  const auto& g = s.grid();
  for (int j = 0; j < g.cells[1]; ++j)
    for (int i = 0; i < g.cells[0]; ++i) {
      EXPECT_NEAR(gp[0](i, j, 0), -3.0, 1e-9);
      EXPECT_NEAR(gp[1](i, j, 0), 0.0, 1e-9);
    }
}

}  // namespace
}  // namespace gf::fluid
