// Fluid forces: each formula against hand values and directions; toggles; virtual-mass state;
// derived fluid fields (vorticity, viscous stress divergence).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "coupling/forces.hpp"
#include "coupling/interpolation.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

TEST(Forces, PressureViscousBuoyancyHandValues) {
  const double v = force::sphereVolume(2e-3);  // pi/6 * 8e-9 = 4.18879e-9 m^3
  EXPECT_NEAR(v, 4.18879e-9, 1e-14);
  EXPECT_NEAR(force::pressureGradient(v, {0, 0, -9810.0}).z, 4.18879e-9 * 9810.0, 1e-10);
  EXPECT_NEAR(force::viscousStress(v, {2e-3, 0, 0}).x, 8.37758e-12, 1e-17);
  EXPECT_NEAR(force::buoyancy(1000.0, v, {0, 0, -9.81}).z, 4.10920e-5, 1e-10);
}

TEST(Forces, SaffmanMeiLiftHandValueAndDirection) {
  // d = 1 mm, water, slip (0.01, 0, 0), vorticity (0, 0, 10): Re = 10, Re_w = 10, b = 0.5,
  // Mei: (1 - 0.3314 sqrt(0.5)) e^-1 + 0.3314 sqrt(0.5) = 0.765666 * 0.367879 + 0.234334 = 0.516008;
  // Saffman: 1.615 d^2 sqrt(rho mu / |w|) |slip x w| = 1.615e-6 * 0.316228 * 0.1 = 5.10708e-8 N
  // (= 6.46 mu a^2 U sqrt(G / nu) with a = 0.5 mm, G = 10/s); slip x w = (0, -0.1, 0).
  EXPECT_NEAR(force::meiCorrection(10.0, 10.0), 0.516008, 1e-6);
  EXPECT_NEAR(force::meiCorrection(100.0, 10.0), 0.0524 * std::sqrt(0.05 * 100.0), 1e-12);  // Re > 40 branch
  const Vec3 f = force::saffmanMeiLift(1000.0, 1e-3, 1e-3, {0.01, 0, 0}, {0, 0, 10.0});
  EXPECT_NEAR(f.y, -5.10708e-8 * 0.516008, 1e-13);
  EXPECT_EQ(f.x, 0.0);
  // shear flow u = (G y, 0, 0): curl u = (0, 0, -G); a lagging particle (slip +x) moves to +y, towards faster fluid
  EXPECT_GT(force::saffmanMeiLift(1000.0, 1e-3, 1e-3, {0.01, 0, 0}, {0, 0, -10.0}).y, 0.0);
  EXPECT_EQ(norm(force::saffmanMeiLift(1000.0, 1e-3, 1e-3, {0.01, 0, 0}, {})), 0.0);
}

TEST(Forces, MagnusLiftAndRotationalTorque) {
  // sphere d = 1 mm spinning at 100 rad/s about z, moving at 0.1 m/s along x in still water:
  // F = pi/8 d^3 rho (omega x v) = 0.392699 * 1e-9 * 1000 * (0, 10, 0) = (0, 3.92699e-6, 0) N
  const Vec3 rel = force::relativeRotation({0, 0, 100.0}, {});
  const Vec3 f = force::magnusLift(1000.0, 1e-3, rel, Vec3{-0.1, 0, 0});
  EXPECT_NEAR(f.y, 3.92699e-6, 1e-11);
  // torque -pi mu d^3 omega = -3.14159e-9 * 1e-3 * 100 = -3.14159e-10 N m
  EXPECT_NEAR(force::rotationalTorque(1e-3, 1e-3, rel).z, -3.14159e-10, 1e-15);
  // co-rotating with the fluid (omega_p = curl u / 2): no torque, no Magnus lift
  const Vec3 corot = force::relativeRotation({0, 0, 5.0}, {0, 0, 10.0});
  EXPECT_EQ(norm(force::rotationalTorque(1e-3, 1e-3, corot)), 0.0);
  EXPECT_EQ(norm(force::magnusLift(1000.0, 1e-3, corot, {1, 0, 0})), 0.0);
}

TEST(Forces, VorticityAndViscousStressDivergenceOnTheGrid) {
  const CartesianGrid g = makeGrid({6, 8, 5}, {0.01, 0.01, 0.01});
  const GridTopology topo{g, {false, false, false}};
  FluidFields fluid(g);
  // u = (G y + y^2 / L, 0, 0): curl_z = -(G + 2 y / L), laplace u_x = 2 / L
  const double G = 3.0, L = 0.5;
  fluid.setVelocity(g, [&](const Vec3& x) { return Vec3{G * x.y + x.y * x.y / L, 0.0, 0.0}; });
  const Field* const u[3] = {&fluid.u[0], &fluid.u[1], &fluid.u[2]};
  Field curl[3] = {Field(g), Field(g), Field(g)}, divTau[3] = {Field(g), Field(g), Field(g)};
  computeVorticity(topo, u, curl);
  computeViscousStressDivergence(topo, u, 1e-3, divTau);
  for (int k = 0; k < 5; ++k)
    for (int j = 1; j < 7; ++j)  // central differences exact for quadratics away from walls
      for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(curl[2](i, j, k), -(G + 2.0 * g.cellCentre(i, j, k).y / L), 1e-10);
        EXPECT_NEAR(divTau[0](i, j, k), 1e-3 * 2.0 / L, 1e-9);
        EXPECT_NEAR(curl[0](i, j, k), 0.0, 1e-12);
      }
}

TEST(Forces, TogglesSelectWhatActsOnParticles) {
  const CartesianGrid g = makeGrid({4, 4, 4}, {0.01, 0.01, 0.01});
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3&) { return Vec3{0.1, 0, 0}; });
  fluid.setPressureGradient(g, [](const Vec3&) { return Vec3{0, 0, -9810.0}; });
  dem::ParticleSet one;
  one.add(0, 0, 0.001, 2500.0, g.cellCentre(1, 2, 1));
  const std::string off = "  forces:\n    drag: false\n    pressure_gradient: false\n    viscous_stress: false\n";
  {
    auto c = makeCoupler(off, g);
    CouplingFields f(g);
    c->computeVoidFraction(one, f);
    c->computeParticleForces(fluid.view(1000.0, 1e-3), f, one);
    EXPECT_EQ(norm(one.externalForce[0]), 0.0);
  }
  {
    // the prescribed velocity is taken as the particle's cell velocity (no flux reconstruction)
    auto c = makeCoupler("  interpolation: cell\n  void_fraction: pcm\n  drag_law: stokes\n"
                         "  velocity_reconstruction: face_mean\n  forces:\n    pressure_gradient: false\n    viscous_stress: false\n",
                         g);
    CouplingFields f(g);
    c->computeVoidFraction(one, f);
    c->computeParticleForces(fluid.view(1000.0, 1e-3), f, one);
    // Stokes: 3 pi mu d u = 3 pi * 1e-3 * 2e-3 * 0.1 = 1.884956e-6 N
    EXPECT_NEAR(one.externalForce[0].x, 1.884956e-6, 1e-12);
    EXPECT_NEAR(c->dragCoefficients()[0], 1.884956e-5, 1e-11);
  }
  {
    auto c = makeCoupler("  forces:\n    drag: false\n    viscous_stress: false\n    buoyancy: true\n", g,
                         {false, false, false}, {0, 0, -9.81});
    CouplingFields f(g);
    c->computeVoidFraction(one, f);
    c->computeParticleForces(fluid.view(1000.0, 1e-3), f, one);
    const double v = force::sphereVolume(2e-3);  // -V grad p + buoyancy -rho_f V g, both upwards
    EXPECT_NEAR(one.externalForce[0].z, v * 9810.0 + 1000.0 * v * 9.81, 1e-15);
  }
}

TEST(Forces, VirtualMassUsesSlipChangeOverTheCouplingIntervalAndSurvivesRestart) {
  const CartesianGrid g = makeGrid({4, 4, 4}, {0.01, 0.01, 0.01});
  FluidFields fluid(g);
  dem::ParticleSet one;
  one.add(7, 0, 0.001, 2500.0, g.cellCentre(1, 1, 1));
  const std::string yaml = "  velocity_reconstruction: face_mean\n"  // the prescribed velocity as given
                           "  forces:\n    drag: false\n    pressure_gradient: false\n    viscous_stress: false\n"
                           "    virtual_mass: true\n";
  auto c = makeCoupler(yaml, g);
  CouplingFields f(g);
  c->computeVoidFraction(one, f);
  c->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), f, one);
  EXPECT_EQ(norm(one.externalForce[0]), 0.0);  // first step: no history
  BinaryWriter w;
  c->save(w, one);
  // fluid accelerates by 0.2 m/s in dt = 1e-3: F = 0.5 * 1000 * V * 0.2 / 1e-3 = 1e5 V
  fluid.setVelocity(g, [](const Vec3&) { return Vec3{0.2, 0, 0}; });
  c->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), f, one);
  const double expected = 0.5 * 1000.0 * force::sphereVolume(2e-3) * 0.2 / 1e-3;
  EXPECT_NEAR(one.externalForce[0].x, expected, 1e-12 * expected);
  // a restarted coupler with the saved state (restored into the particles' columns by id) gives
  // the same force
  auto restarted = makeCoupler(yaml, g);
  dem::ParticleSet again = one;
  BinaryReader r(w.bytes().data(), w.bytes().size());
  restarted->load(r, again);
  EXPECT_TRUE(r.atEnd());
  CouplingFields f2(g);
  restarted->computeVoidFraction(again, f2);
  restarted->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), f2, again);
  EXPECT_EQ(again.externalForce[0], one.externalForce[0]);
}

TEST(Forces, VirtualMassHistoryFollowsParticlesWhenTheDemReordersThem) {
  const CartesianGrid g = makeGrid({5, 5, 5}, {0.01, 0.01, 0.01});
  const std::string yaml = "  velocity_reconstruction: face_mean\n"  // the prescribed velocity as given
                           "  forces:\n    drag: false\n    pressure_gradient: false\n    viscous_stress: false\n"
                           "    virtual_mass: true\n";
  const dem::ParticleSet base = randomParticles(50, 0.001, 0.002, {0, 0, 0}, {0.05, 0.05, 0.05});
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3& x) { return Vec3{x.y, -x.x, 0.1}; });
  auto first = makeCoupler(yaml, g), second = makeCoupler(yaml, g);
  dem::ParticleSet a = base, b = base;
  CouplingFields fa(g), fb(g);
  first->computeVoidFraction(a, fa);
  second->computeVoidFraction(b, fb);
  first->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), fa, a);
  second->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), fb, b);
  // the "DEM" of the second run reverses the order (ParticleSet::gather moves the history along)
  dem::ParticleSet reversed = b;
  std::vector<std::uint32_t> order(b.size());
  for (std::size_t q = 0; q < order.size(); ++q) order[q] = static_cast<std::uint32_t>(b.size() - 1 - q);
  reversed.gather(order);
  fluid.setVelocity(g, [](const Vec3& x) { return Vec3{2.0 * x.y, -x.x, 0.3}; });
  first->computeVoidFraction(a, fa);
  second->computeVoidFraction(reversed, fb);
  first->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), fa, a);
  second->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), fb, reversed);
  for (std::size_t p = 0; p < a.size(); ++p) {
    EXPECT_GT(norm(a.externalForce[p]), 0.0);
    EXPECT_EQ(a.externalForce[p], reversed.externalForce[a.size() - 1 - p]);
  }
}
