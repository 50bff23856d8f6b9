// Coupling-interval criterion of seed 000 (eqs. 5.22, 5.30; tables 5.4, 5.5).
#include <gtest/gtest.h>

#include "coupling/coupling_interval.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf::coupling;

namespace {
// seed 000 table 5.3: air at 20 C, glass
constexpr double kAirDensity = 1.1885, kAirNu = 1.532e-5, kGlass = 2500.0;
constexpr double kAirMu = kAirDensity * kAirNu;  // 1.82078e-5 Pa s
}  // namespace

TEST(CouplingInterval, RelaxationTimesOfTable54) {
  // seed 000 table 5.4: tau_p = 7.63 s for d = 1 mm and 7.63e-2 s for d = 0.1 mm (creeping limit)
  EXPECT_NEAR(particleRelaxationTime(kGlass, 1e-3, kAirMu, 0.0), 7.63, 0.01);
  EXPECT_NEAR(particleRelaxationTime(kGlass, 1e-4, kAirMu, 0.0), 7.63e-2, 1e-4);
  // Re = 10: drag larger by 1 + 0.15 * 10^0.687 = 1.729611 -> tau = 7.62798e-2 / 1.729611 = 4.41023e-2 s
  EXPECT_NEAR(particleRelaxationTime(kGlass, 1e-4, kAirMu, 10.0), 4.41023e-2, 1e-7);
}

TEST(CouplingInterval, ScalingLawReproducesTable55) {
  // Table 5.5: tau_c = 1e-3 s for d1 = 0.1 mm corresponds to 1.4e-5, 1.13e-4, 2.9e-4 s for
  // d2 = 10, 30, 50 um. The slip of the original particle is not printed; solving the first
  // entry for it gives 1.047 m/s (Re1 = 6.83); with it eq. 5.30 must give the other entries.
  const double slip = 1.047;
  EXPECT_NEAR(scaledCouplingInterval(1e-3, 1e-4, 1e-5, slip, kAirNu), 1.4e-5, 0.01 * 1.4e-5);
  EXPECT_NEAR(scaledCouplingInterval(1e-3, 1e-4, 3e-5, slip, kAirNu), 1.13e-4, 0.01 * 1.13e-4);
  EXPECT_NEAR(scaledCouplingInterval(1e-3, 1e-4, 5e-5, slip, kAirNu), 2.9e-4, 0.01 * 2.9e-4);
  // second row (5e-4 s): 7.0e-6, 5.65e-5, 1.45e-4 (linear in tau_c,1)
  EXPECT_NEAR(scaledCouplingInterval(5e-4, 1e-4, 3e-5, slip, kAirNu), 5.65e-5, 0.01 * 5.65e-5);
  EXPECT_NEAR(scaledCouplingInterval(5e-4, 1e-4, 5e-5, slip, kAirNu), 1.45e-4, 0.01 * 1.45e-4);
}

TEST(CouplingInterval, WarnsWhenIntervalOrDemStepIsTooLong) {
  // d = 10 um glass in air at small slip: tau_p = 7.63e-4 s.
  const auto ok = checkCouplingInterval(1e-6, 50, kGlass, 1e-5, kAirDensity, kAirMu, 0.0, 10.0);
  EXPECT_TRUE(ok.warning.empty()) << ok.warning;
  EXPECT_NEAR(ok.ratio, 7.6284e-4 / 5e-5, 0.01);
  const auto tooLong = checkCouplingInterval(1e-6, 200, kGlass, 1e-5, kAirDensity, kAirMu, 0.0, 10.0);
  EXPECT_NE(tooLong.warning.find("at most 76 DEM steps"), std::string::npos) << tooLong.warning;
  // DEM step longer than tau_p (d = 0.2 um: tau_p = 3.05e-7 s, table 5.4): explicit drag unstable
  const auto unstable = checkCouplingInterval(1e-6, 1, kGlass, 2e-7, kAirDensity, kAirMu, 0.0, 10.0);
  EXPECT_NE(unstable.warning.find("unstable"), std::string::npos) << unstable.warning;
}

TEST(CouplingInterval, CouplerChecksSmallestPrimaryParticle) {
  const gf::CartesianGrid g = gf::coupling::testing::makeGrid({4, 4, 4}, {0.01, 0.01, 0.01});
  auto c = gf::coupling::testing::makeCoupler("  coarse_grain_factor: 2\n", g);
  gf::dem::ParticleSet s;
  s.add(0, 0, 1e-4, kGlass, g.cellCentre(1, 1, 1));  // parcel d = 0.2 mm -> primary 0.1 mm
  s.add(1, 0, 5e-5, kGlass, g.cellCentre(2, 1, 1));  // parcel d = 0.1 mm -> primary 50 um (fastest)
  gf::coupling::testing::FluidFields fluid(g);
  const auto check = c->checkCouplingInterval(1e-5, 100, s, fluid.view(kAirDensity, kAirMu), 0.0);
  EXPECT_NEAR(check.relaxationTime, 7.6284e-2 / 4.0, 1e-4);
  EXPECT_NEAR(check.couplingInterval, 1e-3, 1e-15);
  EXPECT_TRUE(check.warning.empty());
}
