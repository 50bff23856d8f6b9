// The pure formulas of the phase-fraction transport (src/vof/kernels.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "vof/kernels.hpp"

namespace k = gf::vof::kernels;

TEST(VofKernels, LaxWendroffIncrementIsCentralAtZeroCourantAndUpwindAtOne) {
  EXPECT_DOUBLE_EQ(k::laxWendroffIncrement(0.2, 0.8, 0.0), 0.3);  // face value 0.5: central
  EXPECT_DOUBLE_EQ(k::laxWendroffIncrement(0.2, 0.8, 1.0), 0.0);  // exact shift by one cell
  EXPECT_DOUBLE_EQ(k::laxWendroffIncrement(0.2, 0.8, 0.5), 0.15);
  EXPECT_DOUBLE_EQ(k::laxWendroffIncrement(0.2, 0.8, 3.0), 0.0);  // clipped
}

TEST(VofKernels, PairNormalIsAUnitVectorAwayFromUniformRegions) {
  const double nx = k::pairNormal(3.0, 4.0, 0.0, 0, 1e-8), ny = k::pairNormal(3.0, 4.0, 0.0, 1, 1e-8);
  EXPECT_NEAR(nx * nx + ny * ny, 1.0, 1e-8);
  EXPECT_EQ(k::pairNormal(0.0, 0.0, 0.0, 2, 1e-8), 0.0);  // no interface: no compression
}

TEST(VofKernels, PairCompressionFluxMovesPhaseIUpItsGradientAndIsAntisymmetric) {
  // alpha_i rises from P (0.2) to N (0.8), alpha_j = 1 - alpha_i: the normal points P -> N (phiR > 0)
  const double f = k::pairCompressionFlux(2.0, 0.2, 0.8, 0.8, 0.2);
  EXPECT_DOUBLE_EQ(f, 2.0 * 0.2 * 0.2);  // phase i from P into N: steepens the profile
  EXPECT_GT(f, 0.0);
  EXPECT_DOUBLE_EQ(k::pairCompressionFlux(-2.0, 0.8, 0.2, 0.2, 0.8), -f);  // the pair (j, i)
  EXPECT_DOUBLE_EQ(k::pairCompressionFlux(2.0, 0.0, 0.8, 1.0, 0.2), 0.0);  // nothing of i upwind
  EXPECT_DOUBLE_EQ(k::pairCompressionFlux(2.0, 0.2, 1.0, 0.8, 0.0), 0.0);  // N already full of i
}

TEST(VofKernels, ZalesakRatioAndFaceFactor) {
  EXPECT_DOUBLE_EQ(k::zalesakRatio(0.5, 1.0), 0.5);
  EXPECT_DOUBLE_EQ(k::zalesakRatio(2.0, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(k::zalesakRatio(-1e-17, 1.0), 0.0);  // no room (round-off below the bound)
  EXPECT_DOUBLE_EQ(k::zalesakRatio(0.3, 0.0), 1.0);     // no correction asks
  // a >= 0 enters U and leaves L: min(R+_U, R-_L); a < 0: min(R+_L, R-_U)
  EXPECT_DOUBLE_EQ(k::faceFactor(1.0, 0.1, 0.2, 0.3, 0.4), 0.2);
  EXPECT_DOUBLE_EQ(k::faceFactor(-1.0, 0.1, 0.2, 0.3, 0.4), 0.1);
}

TEST(VofKernels, LimitSumZeroesTheSumAndOnlyShrinks) {
  double c[4] = {0.3, -0.1, -0.05, 0.02};
  const double before[4] = {0.3, -0.1, -0.05, 0.02};
  k::limitSum(c, 4);
  EXPECT_NEAR(c[0] + c[1] + c[2] + c[3], 0.0, 1e-17);
  for (int i = 0; i < 4; ++i) {
    EXPECT_GE(c[i] * before[i], 0.0);                  // sign kept
    EXPECT_LE(std::abs(c[i]), std::abs(before[i]));    // magnitude not increased
  }
  EXPECT_DOUBLE_EQ(c[1], -0.1);  // the smaller (negative) side is left alone
  double d[3] = {-0.4, 0.1, 0.1};
  k::limitSum(d, 3);
  EXPECT_NEAR(d[0] + d[1] + d[2], 0.0, 1e-17);
  EXPECT_DOUBLE_EQ(d[1], 0.1);
}
