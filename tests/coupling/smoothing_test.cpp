// Implicit-diffusion smoothing (I - l^2 laplace) phi_new = phi_old: conservation, convergence to
// the analytic impulse response exp(-|x|/l) / (2 l), and the Coupler path (eps and exchange fields).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "coupling/smoothing.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

namespace {
double interiorSum(const Field& f) {
  const CartesianGrid& g = f.grid();
  double s = 0.0;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) s += f(i, j, k);
  return s;
}
}  // namespace

TEST(Smoothing, ConservesTheIntegralWithWallsAndPeriodicBoundaries) {
  const CartesianGrid g = makeGrid({12, 9, 15}, {0.01, 0.012, 0.008});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::array<bool, 3> periodic : {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true}}) {
    Field f(g);
    for (auto& v : f.data()) v = u(rng) < 0.1 ? u(rng) : 0.0;
    const double before = interiorSum(f);
    const SmoothingReport r = smoothField(GridTopology{g, periodic}, 0.02, f);
    EXPECT_GT(r.iterations, 0);
    EXPECT_NEAR(interiorSum(f) / before, 1.0, 1e-12);
    double maxValue = 0.0, minValue = 1.0;
    for (int k = 0; k < 15; ++k)
      for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 12; ++i) {
          maxValue = std::max(maxValue, f(i, j, k));
          minValue = std::min(minValue, f(i, j, k));
        }
    EXPECT_GE(minValue, 0.0);  // M-matrix: positivity preserved
    EXPECT_LT(maxValue, 0.5);  // peaks spread out
  }
}

TEST(Smoothing, ImpulseResponseConvergesToAnalyticSolutionAtSecondOrder) {
  // 1D line of length 20 l (walls far away), unit impulse in the middle cell: the exact response of
  // (1 - l^2 d2/dx2) phi = delta is exp(-|x| / l) / (2 l). Max error at the cell centres shrinks as
  // dx^2 as the grid is refined (l fixed).
  const double l = 0.01, length = 20.0 * l;
  double previousError = 0.0;
  for (int n : {41, 81, 161, 321}) {
    const double dx = length / n;
    const CartesianGrid g = makeGrid({n, 1, 1}, {dx, 1.0, 1.0}, {-0.5 * length, 0.0, 0.0});
    Field f(g);
    f(n / 2, 0, 0) = 1.0 / dx;
    smoothField(GridTopology{g, {false, false, false}}, l, f);
    double error = 0.0;
    for (int i = 0; i < n; ++i) {
      const double x = g.cellCentre(i, 0, 0).x;
      error = std::max(error, std::abs(f(i, 0, 0) - std::exp(-std::abs(x) / l) / (2.0 * l)));
    }
    if (previousError > 0.0) {
      EXPECT_GT(std::log2(previousError / error), 1.8) << "n = " << n;
    }
    previousError = error;
  }
  EXPECT_LT(previousError, 1e-3 / (2.0 * l));  // finest grid within 0.1 % of the peak
}

TEST(Smoothing, CouplerSmoothsVoidFractionConservativelyAndWidensItWithLength) {
  const double dx = 0.005;
  const CartesianGrid g = makeGrid({20, 4, 20}, {dx, dx, dx});
  const dem::ParticleSet particles = randomParticles(60, 0.001, 0.002, {0.04, 0.0, 0.04}, {0.06, 0.02, 0.06});
  double previousPeak = 2.0;
  for (double l : {0.0, 0.005, 0.01, 0.02}) {
    auto c = makeCoupler("  void_fraction: pcm\n  min_void_fraction: 0\n  smoothing_length: " + std::to_string(l) + "\n",
                         g, {false, true, false});
    CouplingFields f(g);
    c->computeVoidFraction(particles, f);
    EXPECT_NEAR(solidVolume(f.voidFraction) / c->particleVolume(), 1.0, 1e-11) << l;
    double peak = 0.0;
    for (int k = 0; k < 20; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 20; ++i) peak = std::max(peak, 1.0 - f.voidFraction(i, j, k));
    EXPECT_LT(peak, previousPeak) << l;  // longer smoothing length: lower peak solid fraction
    previousPeak = peak;
  }
}

TEST(Smoothing, SmoothedExplicitExchangeFieldsKeepNewtonsThirdLaw) {
  const CartesianGrid g = makeGrid({10, 10, 10}, {0.01, 0.01, 0.01});
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3& x) { return Vec3{0.1 + x.y, 0.0, -0.05}; });
  dem::ParticleSet particles = randomParticles(200, 0.001, 0.003, {0, 0, 0}, {0.1, 0.1, 0.1});
  auto c = makeCoupler("  exchange: explicit\n  smoothing_length: 0.015\n  smooth_exchange_fields: true\n", g);
  CouplingFields f(g);
  c->computeVoidFraction(particles, f);
  c->computeParticleForces(fluid.view(1000.0, 1e-3), f, particles);
  c->fillFluidSources(f);
  EXPECT_LT(norm(c->momentumBalanceError()), 1e-11 * c->exchangedForceScale());
}

TEST(Smoothing, ParcelSmoothingLengthScalesWithInverseCubeRootOfConcentration) {
  // seed 003 eq. 4.10: l/d32 = (l/d32)_ref / (10 phi^(1/3)) for phi_ref = 1e-3; table 4.15: 8.06 d32.
  const double d32 = 1e-4;
  EXPECT_NEAR(scaledSmoothingLength(8.06 * d32, 1e-3, 1e-3), 8.06 * d32, 1e-15);
  EXPECT_NEAR(scaledSmoothingLength(8.06 * d32, 1e-3, 0.008), 8.06 * d32 / (10.0 * 0.2), 1e-15);
  EXPECT_NEAR(scaledSmoothingLength(8.06 * d32, 1e-3, 0.125), 8.06 * d32 / (10.0 * 0.5), 1e-15);
}
