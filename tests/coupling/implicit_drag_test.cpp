// Semi-implicit drag update (seed 000 eq. 5.26): stable for DEM steps beyond the relaxation time,
// where the explicit update oscillates and diverges (seed 000 table 5.4).
#include <gtest/gtest.h>

#include <cmath>

#include "coupling/implicit_drag.hpp"

using gf::Vec3;

TEST(ImplicitDrag, ConvergesToTerminalSlipForAnyStepWhereExplicitDiverges) {
  const double mass = 1e-6, beta = 1e-3;  // tau_p = m / beta = 1e-3 s
  const Vec3 u{0.0, 0.0, 0.2}, weight{0.0, 0.0, -9.81 * mass};
  const Vec3 terminal = u + weight / beta;  // beta (u - v) + W = 0
  const double dt = 5e-3;                  // 5 tau_p
  Vec3 implicitV{}, explicitV{};
  for (int n = 0; n < 60; ++n) {
    implicitV = gf::coupling::semiImplicitDragVelocity(implicitV, u, beta, mass, weight, dt);
    explicitV = explicitV + (dt / mass) * (weight + beta * (u - explicitV));
  }
  EXPECT_NEAR(implicitV.z, terminal.z, 1e-12);
  EXPECT_GT(std::abs(explicitV.z - terminal.z), 1e6 * std::abs(terminal.z));  // |1 - dt/tau| = 4 per step
  // small steps: backward Euler converges to v(t) = v_t (1 - exp(-t/tau)) at first order
  auto errorAt = [&](int steps) {
    Vec3 v{};
    const double h = 1e-3 / steps;  // integrate to t = tau
    for (int n = 0; n < steps; ++n) v = gf::coupling::semiImplicitDragVelocity(v, u, beta, mass, weight, h);
    return std::abs(v.z - terminal.z * (1.0 - std::exp(-1.0)));
  };
  const double e1 = errorAt(100), e2 = errorAt(200);
  EXPECT_LT(e1, 2e-3 * std::abs(terminal.z));
  EXPECT_NEAR(e1 / e2, 2.0, 0.05);
}
