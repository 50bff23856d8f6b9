// Coarse graining per insertion (insertion[].coarse_graining = alpha, seed 003 eq. 3.34): a parcel
// of diameter alpha d of an insertion with factor alpha, next to a primary particle of diameter d
// of another insertion, in the same cell of the same flow, feels alpha^3 times the primary's drag
// (to round-off: the law sees d_prim = d and the same slip and eps). With the filtered correction
// each parcel takes c_corr of its own alpha (seed 003 eq. 3.36). The DEM rejects alpha < 1 with
// the file, line and key, and two factors for one material.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "coupling/coarse_graining.hpp"
#include "coupling/drag/filtered.hpp"
#include "coupling_test_helpers.hpp"
#include "../dem/dem_test_util.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

namespace {

/// Force on a primary particle (material 0, alpha 1, d = 1 mm) and a parcel (material 1, alpha,
/// d = alpha mm) side by side in the centre cell of a uniform flow; drag only.
struct Pair {
  Vec3 primary, parcel;
  double betaPrimary = 0.0, betaParcel = 0.0;
};

Pair forcesOf(const std::string& law, double alpha, const std::string& extra = "") {
  const double dx = 0.02;
  const CartesianGrid g = makeGrid({3, 3, 3}, {dx, dx, dx});
  dem::ParticleSet s;
  const Vec3 centre = g.cellCentre(1, 1, 1);
  s.add(0, 0, 0.0005, 2500.0, centre + Vec3{-0.004, 0.0, 0.0}, {0.0, 0.0, -0.05});
  s.add(1, 1, 0.0005 * alpha, 2500.0, centre + Vec3{0.004, 0.0, 0.0}, {0.0, 0.0, -0.05});
  auto c = makeCoupler("  drag_law: " + law +
                           "\n  void_fraction: pcm\n  interpolation: cell\n  forces:\n    pressure_gradient: false\n"
                           "    viscous_stress: false\n" + extra,
                       g);
  c->setCoarseGrainingByMaterial({0.0, alpha});  // material 0: none given (coarse_grain_factor 1)
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3&) { return Vec3{0.01, 0.0, 0.02}; });
  CouplingFields f(g);
  c->computeVoidFraction(s, f);
  c->computeParticleForces(fluid.view(1000.0, 1e-3), f, s);
  return {s.externalForce[0], s.externalForce[1], c->dragCoefficients()[0], c->dragCoefficients()[1]};
}

}  // namespace

TEST(CoarseGrainingPerInsertion, ParcelDragIsAlphaCubedPrimaryDragInTheSameFlow) {
  for (const char* law : {"di_felice", "beetstra", "gidaspow", "beetstra_polydisperse"})
    for (double alpha : {2.0, 3.0, 10.0}) {
      const Pair p = forcesOf(law, alpha);
      const double k3 = alpha * alpha * alpha;
      EXPECT_GT(norm(p.primary), 0.0) << law;
      EXPECT_NEAR(p.betaParcel, k3 * p.betaPrimary, 1e-12 * p.betaParcel) << law << " alpha " << alpha;
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(p.parcel[a], k3 * p.primary[a], 1e-12 * norm(p.parcel)) << law << " alpha " << alpha;
    }
}

TEST(CoarseGrainingPerInsertion, FilteredCorrectionTakesEachParcelsOwnFactor) {
  const double alpha = 10.0;
  const Pair p = forcesOf("beetstra", alpha,
                          "  drag_correction: filtered\n  filtered_drag:\n    primary_diameter: 0.001\n");
  // c_corr(alpha) / c_corr(1) = exp(-0.05 (alpha - 1)) (seed 003 eq. 3.36, a = 0, k = 0.05)
  const double ratio = drag::parcelDragCorrection(alpha) / drag::parcelDragCorrection(1.0);
  EXPECT_NEAR(ratio, std::exp(-0.05 * 9.0), 1e-15);
  EXPECT_NEAR(p.betaParcel, alpha * alpha * alpha * ratio * p.betaPrimary, 1e-12 * p.betaParcel);
}

TEST(CoarseGrainingPerInsertion, FactorsPerMaterialFallBackToTheCouplingFactor) {
  CoarseGraining cg(2.0);
  cg.setByMaterial({0.0, 5.0, 0.0});
  EXPECT_FALSE(cg.uniform());
  EXPECT_EQ(cg.factorOf(0), 2.0);
  EXPECT_EQ(cg.factorOf(1), 5.0);
  EXPECT_EQ(cg.largest(), 5.0);
  EXPECT_EQ(cg.particlesPerParcelByMaterial[1], 125.0);
  CoarseGraining same(1.0);
  same.setByMaterial({4.0, 4.0});
  EXPECT_TRUE(same.uniform());  // one factor: the scalar path of the force pass
  EXPECT_EQ(same.factor, 4.0);
}

namespace {
std::string demCase(const std::string& insertions) {
  return R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: a, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
  - {name: b, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
insertion:
)" + insertions;
}
std::string insertion(const std::string& material, const std::string& factor, double diameter) {
  return "  - {type: random_packing, material: " + material + ", min: [0, 0, 0], max: [0.01, 0.01, 0.01], count: 5, "
         "size: {distribution: constant, diameter: " + std::to_string(diameter) + "}" +
         (factor.empty() ? "" : ", coarse_graining: " + factor) + "}\n";
}
}  // namespace

TEST(CoarseGrainingPerInsertion, InsertionFactorsReachTheMaterials) {
  dem::test::DemCase c(demCase(insertion("a", "", 0.001) + insertion("b", "10", 0.001)), {0, 0, -9.81});
  const std::vector<double> f = c->coarseGrainingByMaterial();
  ASSERT_GE(f.size(), 2u);  // (and the built-in rigid wall material)
  EXPECT_EQ(f[0], 0.0);  // not given: coupling.coarse_grain_factor applies
  EXPECT_EQ(f[1], 10.0);
}

TEST(CoarseGrainingPerInsertion, FactorBelowOneIsRejectedWithFileLineAndKey) {
  try {
    dem::test::DemCase c(demCase(insertion("a", "0.5", 0.001)), {0, 0, -9.81});
    FAIL() << "coarse_graining: 0.5 accepted";
  } catch (const CaseError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("test.yaml:6:"), std::string::npos) << what;
    EXPECT_NE(what.find("coarse_graining"), std::string::npos) << what;
  }
}

TEST(CoarseGrainingPerInsertion, TwoFactorsForOneMaterialAreRejected) {
  try {
    dem::test::DemCase c(demCase(insertion("a", "2", 0.001) + insertion("a", "3", 0.001)), {0, 0, -9.81});
    FAIL() << "two factors for material a accepted";
  } catch (const CaseError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("coarse_graining"), std::string::npos) << what;
    EXPECT_NE(what.find("material a"), std::string::npos) << what;
  }
}
