// Coarse graining: a parcel of k^3 particles feels k^3 times the fluid force of one primary
// particle in the same surroundings, so it settles like a primary particle; contact scaling keeps
// overlap / diameter under the same stress.
#include <gtest/gtest.h>

#include "coupling/coarse_graining.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

TEST(CoarseGraining, ParcelFeelsParticlesPerParcelTimesPrimaryForce) {
  const double k = 3.0, dx = 0.004, r = 0.0005;
  // The parcel's grid is k times coarser, so both see the same void fraction and (uniform) fields.
  for (const char* law : {"di_felice", "beetstra", "gidaspow", "koch_hill"}) {
    Vec3 force[2];
    double mass[2];
    for (int parcel = 0; parcel < 2; ++parcel) {
      const double scale = parcel ? k : 1.0;
      const CartesianGrid g = makeGrid({5, 5, 5}, {dx * scale, dx * scale, dx * scale});
      dem::ParticleSet s;
      for (int n = 0; n < 3; ++n) s.add(n, 0, r * scale, 2500.0, g.cellCentre(2, 2, 2), {0.0, 0.0, -0.05});
      auto c = makeCoupler(std::string("  drag_law: ") + law + "\n  coarse_grain_factor: " + (parcel ? "3" : "1") +
                               "\n  void_fraction: pcm\n  interpolation: cell\n  forces:\n    virtual_mass: true\n",
                           g);
      FluidFields fluid(g);
      fluid.setVelocity(g, [](const Vec3&) { return Vec3{0.01, 0.0, 0.02}; });
      fluid.setPressureGradient(g, [](const Vec3&) { return Vec3{0.0, 0.0, -9810.0}; });
      CouplingFields f(g);
      c->computeVoidFraction(s, f);
      c->computeParticleForces(fluid.view(1000.0, 1e-3), f, s);
      force[parcel] = s.externalForce[0];
      mass[parcel] = s.mass[0];
    }
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(force[1][a], k * k * k * force[0][a], 1e-12 * norm(force[1])) << law;
    // same force per mass -> same acceleration, same terminal velocity as the primary particle
    EXPECT_NEAR(norm(force[1]) / mass[1], norm(force[0]) / mass[0], 1e-12 * norm(force[0]) / mass[0]);
  }
}

TEST(CoarseGraining, ContactScalingKeepsRelativeOverlapUnderSameStress) {
  const CoarseGraining cg{4.0};
  EXPECT_EQ(cg.particlesPerParcel(), 64.0);
  EXPECT_EQ(cg.primaryDiameter(0.004), 0.001);
  // Linear spring: same stress sigma on a contact area ~ d^2 -> F = sigma d^2; overlap F / k_n.
  const double sigma = 1e4, d = 1e-3, kn = 1e3;
  const double primaryOverlapRatio = sigma * d * d / kn / d;
  const double parcelD = 4.0 * d;
  const double parcelOverlapRatio = sigma * parcelD * parcelD / (kn * cg.linearStiffnessScale()) / parcelD;
  EXPECT_NEAR(parcelOverlapRatio, primaryOverlapRatio, 1e-15);
  // Same restitution: damping ratio zeta = c / (2 sqrt(m k_n)) unchanged with m ~ k^3, k_n ~ k
  const double m = 1e-6, c = 2.0 * 0.3 * std::sqrt(m * kn);
  const double zetaParcel = c * cg.linearDampingScale() / (2.0 * std::sqrt(m * 64.0 * kn * cg.linearStiffnessScale()));
  EXPECT_NEAR(zetaParcel, 0.3, 1e-12);
  // Hertz: F ~ E sqrt(R) delta^1.5 -> with E unchanged, delta/d is the same under the same stress
  const double hertzPrimary = std::pow(sigma * d * d / (std::sqrt(d / 2.0)), 2.0 / 3.0) / d;
  const double hertzParcel =
      std::pow(sigma * parcelD * parcelD / (cg.hertzModulusScale() * std::sqrt(parcelD / 2.0)), 2.0 / 3.0) / parcelD;
  EXPECT_NEAR(hertzParcel, hertzPrimary, 1e-12 * hertzPrimary);
}
