// Drag with several fluids (FluidView::mixtureDensity / mixtureViscosity, fluid.vof): a particle
// takes the density and viscosity of its cell, so in a water cell it feels the drag of water and
// in an air cell the drag of air, the same forces as the single-fluid coupler gives with those
// properties.
#include <gtest/gtest.h>

#include "coupling_test_helpers.hpp"

namespace gf::coupling {
namespace {

using namespace testing;

TEST(MixtureDrag, EachParticleTakesItsCellsDensityAndViscosity) {
  const CartesianGrid g = makeGrid({2, 2, 2}, {0.01, 0.01, 0.01});
  // water below z = 0.01, air above (seed 002 Table 2)
  Field rho(g), mu(g);
  for (int k = -2; k < 4; ++k)
    for (int j = -2; j < 4; ++j)
      for (int i = -2; i < 4; ++i) {
        rho(i, j, k) = k < 1 ? 1000.0 : 1.0;
        mu(i, j, k) = k < 1 ? 1e-3 : 1e-5;
      }
  auto forces = [&](const FluidView& view) {
    auto c = makeCoupler("  drag_law: di_felice\n", g);
    dem::ParticleSet s;
    s.add(0, 0, 0.001, 2500.0, Vec3{0.005, 0.005, 0.005}, Vec3{0.0, 0.0, -0.05}, Vec3{});
    s.add(1, 0, 0.001, 2500.0, Vec3{0.015, 0.015, 0.015}, Vec3{0.0, 0.0, -0.05}, Vec3{});
    CouplingFields f(g);
    c->computeVoidFraction(s, f);
    c->computeParticleForces(view, f, s);
    return std::array<Vec3, 2>{s.externalForce[0], s.externalForce[1]};
  };
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3&) { return Vec3{0.01, 0.0, 0.02}; });
  FluidView mixture = fluid.view(1000.0, 1e-3);
  mixture.mixtureDensity = &rho;
  mixture.mixtureViscosity = &mu;
  const auto both = forces(mixture);
  const auto water = forces(fluid.view(1000.0, 1e-3));
  const auto air = forces(fluid.view(1.0, 1e-5));
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(both[0][a], water[0][a]) << a;
    EXPECT_EQ(both[1][a], air[1][a]) << a;
  }
  EXPECT_GT(std::abs(water[1].z), 10.0 * std::abs(air[1].z));  // (the two fluids differ)
}

}  // namespace
}  // namespace gf::coupling
