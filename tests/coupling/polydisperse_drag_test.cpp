// Polydisperse drag laws (Beetstra et al. 2007, Yin & Sundaresan 2009 / Holloway et al. 2010), the
// filtered drag correction (Radl & Sundaresan 2014) with the parcel correction, size classes and
// per-cell size statistics, the smoothing-length law (seed 003 sec. 3.1.3-3.1.5, Tab. 4.15), and
// their case keys. Reference values were computed independently from the formulas of seed 003 (a
// separate script, values quoted with the inputs).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "coupling/drag/beetstra.hpp"
#include "coupling/drag/beetstra_polydisperse.hpp"
#include "coupling/drag/drag_law.hpp"
#include "coupling/drag/filtered.hpp"
#include "coupling/drag/yin_sundaresan.hpp"
#include "coupling/size_classes.hpp"
#include "coupling/smoothing.hpp"
#include "coupling_test_helpers.hpp"

namespace drag = gf::coupling::drag;
using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

namespace {
std::unique_ptr<DragLaw> makeLaw(const std::string& name) {
  Params p = Params::loadString("x: 0\n", "t.yaml");
  return Registry<DragLaw>::instance().createByName(name, p);
}
}  // namespace

TEST(PolydisperseDrag, BeetstraPolydisperseHandValues) {
  // f = eps [eps y + phi y^2 + 0.064 eps y^3] F*(phi, eps Re / y)   (seed 003 eq. 3.20, F* eq. 3.16)
  // (Re, eps, y) = (0.5, 0.9, 0.6): F*(0.1, 0.75) = 2.478119, bracket 0.588442, f = 1.312406
  // (10, 0.7, 1.5):                 F*(0.3, 4.666667) = 7.482268, bracket 1.876200, f = 9.826762
  // (50, 0.5, 2.0):                 F*(0.5, 12.5) = 23.665929, bracket 3.256000, f = 38.528132
  EXPECT_NEAR(drag::beetstraNormalisedForce(0.9 * 0.5 / 0.6, 0.9), 2.478119, 1e-6);
  EXPECT_NEAR(drag::beetstraPolydisperseFactor(0.6, 0.9), 0.5884416, 1e-12);
  EXPECT_NEAR(drag::beetstraPolydisperse(0.5, 0.9, 0.6), 1.312406, 1e-6);
  EXPECT_NEAR(drag::beetstraPolydisperse(10.0, 0.7, 1.5), 9.826762, 1e-6);
  EXPECT_NEAR(drag::beetstraPolydisperse(50.0, 0.5, 2.0), 38.528132, 1e-5);
  auto law = makeLaw("beetstra_polydisperse");
  EXPECT_TRUE(law->polydisperse());
  EXPECT_EQ(law->polydisperseCorrection(10.0, 0.7, 1.5, 123.0), drag::beetstraPolydisperse(10.0, 0.7, 1.5));
}

TEST(PolydisperseDrag, BeetstraPolydisperseMonodisperseLimit) {
  // y = 1: <Re> = Re, and the published bracket is (1 - phi) + phi + 0.064 (1 - phi) = 1 + 0.064 eps:
  // the law is the monodisperse Beetstra law times 1 + 0.064 eps (to round-off), not the law itself
  // (the 0.064 term is a fit to bidisperse data; see beetstra_polydisperse.hpp).
  for (double eps : {0.45, 0.7, 0.9, 0.999})
    for (double re : {1e-3, 0.5, 20.0, 300.0}) {
      const double mono = drag::beetstra(re, eps);
      EXPECT_NEAR(drag::beetstraPolydisperse(re, eps, 1.0) / (mono * (1.0 + 0.064 * eps)), 1.0, 1e-14)
          << "Re " << re << " eps " << eps;
    }
}

TEST(PolydisperseDrag, YinSundaresanHandValues) {
  // f = eps [1/eps + (F*(phi, eps reMix) - 1/eps)(a y + (1 - a) y^2)],
  // a = 1 - 2.66 phi + 9.096 phi^2 - 11.338 phi^3          (seed 003 eqs. 3.24, 3.28)
  // (reMix, eps, y) = (0.5, 0.9, 0.6): a = 0.813622, F* = 2.455249, f = 1.671723
  // (10, 0.7, 1.5):                    a = 0.714514, F* = 7.824418, f = 8.674249
  // (50, 0.5, 2.0):                    a = 0.526750, F* = 28.116533, f = 39.476182
  EXPECT_NEAR(drag::yinSundaresanWeight(0.1), 0.813622, 1e-12);
  EXPECT_NEAR(drag::yinSundaresanWeight(0.3), 0.714514, 1e-12);
  EXPECT_NEAR(drag::yinSundaresan(0.9, 0.6, 0.5), 1.671723, 1e-6);
  EXPECT_NEAR(drag::yinSundaresan(0.7, 1.5, 10.0), 8.674249, 1e-6);
  EXPECT_NEAR(drag::yinSundaresan(0.5, 2.0, 50.0), 39.476182, 1e-5);
  auto law = makeLaw("yin_sundaresan");
  EXPECT_TRUE(law->polydisperse());
  // the particle's own Re does not enter: only the mixture's
  EXPECT_EQ(law->polydisperseCorrection(999.0, 0.7, 1.5, 10.0), drag::yinSundaresan(0.7, 1.5, 10.0));
}

TEST(PolydisperseDrag, YinSundaresanMonodisperseLimitIsBeetstra) {
  // y = 1 with the particle's slip as the mixture slip: 1/eps + (F* - 1/eps) = F*, the monodisperse
  // Beetstra law, to round-off (1e-12 relative, as the issue asks).
  auto law = makeLaw("yin_sundaresan");
  for (double eps : {0.45, 0.7, 0.9, 0.999})
    for (double re : {1e-3, 0.5, 20.0, 300.0}) {
      EXPECT_NEAR(drag::yinSundaresan(eps, 1.0, re) / drag::beetstra(re, eps), 1.0, 1e-12) << re << " " << eps;
      EXPECT_NEAR(law->correction(re, eps) / drag::beetstra(re, eps), 1.0, 1e-12);
    }
  EXPECT_FALSE(makeLaw("beetstra")->polydisperse());
}

TEST(PolydisperseDrag, FluidMediatedFrictionCoefficients) {
  // eq. 3.27: alpha = 1.313 log10(40 um / 0.1 um) - 1.249 = 1.313 * 2.602060 - 1.249 = 2.167505;
  // clamped at 0 once lambda > 0.112 d
  EXPECT_NEAR(drag::lubricationFactor(40e-6, 1e-7), 2.167505, 1e-6);
  EXPECT_EQ(drag::lubricationFactor(40e-6, 5e-6), 0.0);
  // eq. 3.26: 2 alpha phi_i phi_j / (phi_i/beta_i + phi_j/beta_j), alpha 2.167505, phi 0.01 and 0.03,
  // beta 50 and 400: 2 * 2.167505 * 3e-4 / (2e-4 + 7.5e-5) = 4.729101
  EXPECT_NEAR(drag::pairFrictionCoefficient(2.167505, 0.01, 0.03, 50.0, 400.0), 4.729101, 1e-5);
  // eq. 3.23: 18 phi_i eps mu / d^2 F* = 18 * 0.01 * 0.9 * 2e-5 / 1e-10 * 3 = 97200
  EXPECT_NEAR(drag::classFrictionCoefficient(0.01, 0.9, 2e-5, 1e-5, 3.0), 97200.0, 1e-8);
}

TEST(FilteredDrag, SplineValuesAndKnots) {
  // Radl & Sundaresan (2014) splines, values from the published coefficients:
  // a(0.01) = 21.51 (dilute piece), a(0.05) = 3.6019, a(0.15) = 4.11565, a(0.3) = 2.28949125;
  // h(0.01) = 0.0797, h(0.05) = 0.33206504, h(0.15) = 0.8427016, h(0.3) = 0.94650272
  EXPECT_DOUBLE_EQ(drag::filteredDragA(0.01), 21.51);
  EXPECT_NEAR(drag::filteredDragA(0.05), 3.6019, 1e-12);
  EXPECT_NEAR(drag::filteredDragA(0.15), 4.11565, 1e-12);
  EXPECT_NEAR(drag::filteredDragA(0.3), 2.28949125, 1e-12);
  EXPECT_NEAR(drag::filteredDragH(0.01), 0.0797, 1e-12);
  EXPECT_NEAR(drag::filteredDragH(0.05), 0.33206504, 1e-12);
  EXPECT_NEAR(drag::filteredDragH(0.15), 0.8427016, 1e-12);
  EXPECT_NEAR(drag::filteredDragH(0.3), 0.94650272, 1e-12);
  // h is continuous at its knots to the 3 digits of the published coefficients
  for (double knot : {0.03, 0.08, 0.12, 0.18, 0.34, 0.48, 0.55})
    EXPECT_NEAR(drag::filteredDragH(knot - 1e-12), drag::filteredDragH(knot), 1.5e-3) << knot;
  for (double knot : {0.1, 0.18, 0.25}) EXPECT_NEAR(drag::filteredDragA(knot - 1e-12), drag::filteredDragA(knot), 6e-3);
  EXPECT_EQ(drag::filteredDragH(0.0), 0.0);
}

TEST(FilteredDrag, CorrectionLimitsAndValues) {
  // 1 - h / (L/Delta a + 1):  (phi, Delta, L) = (0.05, 1 mm, 2 mm): 1 - 0.332065 / (2 * 3.6019 + 1) = 0.959523
  // (0.15, 1 cm, 1 mm): 1 - 0.842702 / (0.1 * 4.11565 + 1) = 0.403002; (0.3, 5 mm, 5 mm): 0.712265
  EXPECT_NEAR(drag::filteredDragCorrection(0.05, 1e-3, 2e-3), 0.959523, 1e-6);
  EXPECT_NEAR(drag::filteredDragCorrection(0.15, 1e-2, 1e-3), 0.403002, 1e-6);
  EXPECT_NEAR(drag::filteredDragCorrection(0.3, 5e-3, 5e-3), 0.712265, 1e-6);
  // Delta -> 0 (resolved grid): -> 1; Delta -> infinity: -> 1 - h
  for (double phi : {0.001, 0.05, 0.2, 0.45}) {
    EXPECT_NEAR(drag::filteredDragCorrection(phi, 1e-12, 1e-3), 1.0, 1e-8) << phi;
    EXPECT_NEAR(drag::filteredDragCorrection(phi, 1e12, 1e-3), 1.0 - drag::filteredDragH(phi), 1e-12) << phi;
    double previous = 1.0;  // the correction falls as the filter grows
    for (double delta = 1e-6; delta < 1.0; delta *= 3.0) {
      const double c = drag::filteredDragCorrection(phi, delta, 1e-3);
      EXPECT_LE(c, previous);
      previous = c;
    }
  }
  // parcel correction (eq. 3.36): alpha = 1 -> 1; a = 0, k = 0.05, alpha = 10: exp(-0.45) = 0.637628;
  // a = 0.2, k = 0.1, alpha = 33: 0.2 + 0.8 exp(-3.2) = 0.232610
  EXPECT_EQ(drag::parcelDragCorrection(1.0), 1.0);
  EXPECT_NEAR(drag::parcelDragCorrection(10.0), 0.637628, 1e-6);
  EXPECT_NEAR(drag::parcelDragCorrection(33.0, 0.2, 0.1), 0.232610, 1e-6);
}

TEST(FilteredDrag, TerminalVelocityAndCharacteristicLengthOfTheSeedsParticles) {
  // seed 003 Tab. 4.2-4.3: d = 6.7968 um, rho_p = 2250, rho_f = 0.804 kg/m^3, nu = 3.04e-5 m^2/s.
  // Stokes: u_t = d^2 (rho_p - rho_f) g / (18 mu) = 2.316878e-3 m/s (Re = 5.2e-4, so Beetstra's
  // inertial term lowers it by < 0.1 %); Fr = u_t^2 / (d g) = 0.0805068, L_char = u_t^2/g Fr^-2/3 = 2.93482e-6 m
  const double d = 6.7968e-6, mu = 3.04e-5 * 0.804;
  const double ut = drag::beetstraTerminalVelocity(d, 2250.0, 0.804, mu, 9.81);
  EXPECT_NEAR(ut / 2.3168779e-3, 1.0, 1e-3);
  EXPECT_LT(ut, 2.3168779e-3);
  // the root balances drag and net weight
  const double drag = 3.0 * std::numbers::pi * mu * d * ut * drag::beetstraNormalisedForce(0.804 * ut * d / mu, 1.0);
  EXPECT_NEAR(drag / ((2250.0 - 0.804) * 9.81 * std::numbers::pi * d * d * d / 6.0), 1.0, 1e-12);
  EXPECT_NEAR(drag::filteredDragLength(2.3168779e-3, d, 9.81), 2.934824e-6, 1e-11);
}

TEST(SizeClasses, OneClassPerDistinctDiameterOrLogBins) {
  SizeClasses c({3e-6, 1e-5, 3e-6, 5e-6, 1e-5});
  ASSERT_EQ(c.count(), 3);
  EXPECT_FALSE(c.binned());
  EXPECT_EQ(c.classOf(3e-6), 0);
  EXPECT_EQ(c.classOf(5e-6), 1);
  EXPECT_EQ(c.classOf(1e-5), 2);
  EXPECT_EQ(c.classOf(4.1e-6), 1);  // nearest
  std::vector<double> many;
  for (int i = 0; i < 100; ++i) many.push_back(1e-6 * std::pow(1.05, i));
  SizeClasses b(many);
  EXPECT_TRUE(b.binned());
  EXPECT_EQ(b.count(), SizeClasses::kMaxSizeClasses);
  EXPECT_EQ(b.classOf(many.front()), 0);
  EXPECT_EQ(b.classOf(many.back()), SizeClasses::kMaxSizeClasses - 1);
}

TEST(SizeClasses, CellStatisticsGiveTheSauterMeanAndClassFractions) {
  // one cell of 1 mm^3 with 2 particles of 100 um and 1 of 200 um, coarse-graining factor 2 (primary
  // 50 and 100 um): phi_50 = 2 V(100 um) / 1e-9 = 1.047198e-3, phi_100 = V(200 um) / 1e-9 = 4.188790e-3;
  // <d> = (phi_50 + phi_100) / (phi_50/50um + phi_100/100um) = 83.333 um (eq. 3.5); <v> volume-weighted.
  const CartesianGrid g = makeGrid({2, 1, 1}, {1e-3, 1e-3, 1e-3});
  const GridTopology topology(g, {false, false, false});
  dem::ParticleSet s;
  s.add(0, 0, 50e-6, 2500.0, {2e-4, 5e-4, 5e-4}, {1.0, 0.0, 0.0});
  s.add(1, 0, 50e-6, 2500.0, {4e-4, 5e-4, 5e-4}, {1.0, 0.0, 0.0});
  s.add(2, 0, 100e-6, 2500.0, {6e-4, 5e-4, 5e-4}, {0.0, 0.0, 1.0});
  s.add(3, 0, 100e-6, 2500.0, {1.5e-3, 5e-4, 5e-4}, {0.0, 0.0, 0.0});  // the other cell
  SizeClasses classes({50e-6, 100e-6});
  CellSizeStatistics st;
  std::vector<std::size_t> cellOf;
  std::vector<int> classOf;
  computeCellSizeStatistics(topology, s, CoarseGraining{2.0}, classes, st, cellOf, classOf);
  const std::size_t q = topology.flat(0, 0, 0);
  EXPECT_EQ(cellOf[0], q);
  EXPECT_EQ(classOf[0], 0);
  EXPECT_EQ(classOf[2], 1);
  EXPECT_NEAR(st.classVolumeFraction(q, 0), 1.047198e-3, 1e-9);
  EXPECT_NEAR(st.classVolumeFraction(q, 1), 4.188790e-3, 1e-9);
  EXPECT_NEAR(st.volumeFraction(q), 5.235988e-3, 1e-9);
  EXPECT_NEAR(st.sauterDiameter(q), 83.333333e-6, 1e-12);
  // <v> = (2 V1 (1, 0, 0) + 8 V1 (0, 0, 1)) / 10 V1 = (0.2, 0, 0.8)
  EXPECT_NEAR(st.meanParticleVelocity(q).x, 0.2, 1e-14);
  EXPECT_NEAR(st.meanParticleVelocity(q).z, 0.8, 1e-14);
  EXPECT_NEAR(st.sauterDiameter(topology.flat(1, 0, 0)), 100e-6, 1e-18);
}

TEST(SmoothingLength, AutoLawReproducesTable415AndTheCubeRootScaling) {
  // seed 003 Tab. 4.15 at <phi_p> = 1e-3: l/d32 = 8.06 (alpha 10), 8.06 (25), 10.3 (33), 17.0 (50)
  EXPECT_DOUBLE_EQ(recommendedSmoothingRatio(10.0), 8.06);
  EXPECT_DOUBLE_EQ(recommendedSmoothingRatio(25.0), 8.06);
  EXPECT_DOUBLE_EQ(recommendedSmoothingRatio(33.0), 10.3);
  EXPECT_DOUBLE_EQ(recommendedSmoothingRatio(50.0), 17.0);
  EXPECT_DOUBLE_EQ(recommendedSmoothingRatio(1.0), 8.06);
  EXPECT_NEAR(recommendedSmoothingRatio(41.5), 0.5 * (10.3 + 17.0), 1e-12);
  const double d32 = 6.80e-6;
  EXPECT_NEAR(autoSmoothingLength(33.0, d32, 1e-3), 10.3 * d32, 1e-18);
  // eq. 4.10: 8 x the concentration -> half the length
  EXPECT_NEAR(autoSmoothingLength(10.0, d32, 8e-3), 0.5 * 8.06 * d32, 1e-18);
}

TEST(PolydisperseCoupling, CaseKeysAndTheRefusalOfTheFilteredCorrection) {
  const CartesianGrid g = makeGrid({3, 3, 3}, {0.01, 0.01, 0.01});
  auto c = makeCoupler("  drag_law: beetstra_polydisperse\n  drag_correction: filtered\n  smoothing_length: auto\n"
                       "  filtered_drag:\n    parcel_k: 0.1\n",
                       g);
  EXPECT_EQ(c->settings().dragCorrection, DragCorrection::Filtered);
  EXPECT_TRUE(c->settings().smoothingAuto);
  EXPECT_EQ(c->settings().filteredDrag.parcelK, 0.1);
  EXPECT_EQ(makeCoupler("", g)->settings().dragCorrection, DragCorrection::None);
  EXPECT_NO_THROW(makeCoupler("  drag_law: beetstra\n  drag_correction: filtered\n", g));
  try {
    makeCoupler("  drag_law: gidaspow\n  drag_correction: filtered\n", g);
    FAIL() << "no error";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.yaml:3"), std::string::npos) << msg;  // the line of drag_correction
    EXPECT_NE(msg.find("coupling.drag_correction"), std::string::npos) << msg;
    EXPECT_NE(msg.find("gidaspow"), std::string::npos) << msg;
    EXPECT_NE(msg.find("beetstra or beetstra_polydisperse"), std::string::npos) << msg;
  }
  EXPECT_THROW(makeCoupler("  smoothing_length: automatic\n", g), CaseError);
  EXPECT_THROW(makeCoupler("  drag_correction: filterd\n", g), CaseError);
}

namespace {
/// Three particles in cell (1, 1, 1) of a 3^3 grid of 1 mm cells, in air at rest; interpolation
/// 'cell' and the pcm void fraction, so every particle sees its cell's eps and fluid velocity.
struct PolydisperseCell {
  CartesianGrid g = makeGrid({3, 3, 3}, {1e-3, 1e-3, 1e-3});
  FluidFields fluid{g};
  CouplingFields fields{g};
  dem::ParticleSet s;
  PolydisperseCell() {
    const Vec3 c = g.cellCentre(1, 1, 1);
    s.add(0, 0, 20e-6, 2250.0, c + Vec3{-2e-4, 0, 0}, {0.0, 0.0, -0.02});
    s.add(1, 0, 20e-6, 2250.0, c, {0.0, 0.0, -0.03});
    s.add(2, 0, 60e-6, 2250.0, c + Vec3{2e-4, 0, 0}, {0.0, 0.0, -0.10});
  }
  std::vector<double> betas(const std::string& coupling) {
    auto coupler = makeCoupler("  void_fraction: pcm\n  interpolation: cell\n" + coupling, g);
    dem::ParticleSet copy = s;
    coupler->computeVoidFraction(copy, fields);
    coupler->computeParticleForces(fluid.view(0.804, 2.444e-5), fields, copy);
    return coupler->dragCoefficients();
  }
};
}  // namespace

TEST(PolydisperseCoupling, ForcePassUsesTheCellsSauterMeanAndMixtureSlip) {
  PolydisperseCell cell;
  const std::vector<double> beta = cell.betas("  drag_law: yin_sundaresan\n");
  const double eps = cell.fields.voidFraction(1, 1, 1);
  // <d> = sum V / sum (V/d): V ~ d^3, so <d> = (2 * 40^3 + 120^3) / (2 * 40^2 + 120^2) um = 105.4545 um;
  // <v>_z volume-weighted: (40^3 (-0.02 - 0.03) + 120^3 (-0.10)) / (2 * 40^3 + 120^3) = -0.094828 m/s
  const double v1 = 40.0 * 40 * 40, v2 = 120.0 * 120 * 120;
  const double sauter = (2 * v1 + v2) / (2 * v1 / 40e-6 + v2 / 120e-6);
  EXPECT_NEAR(sauter, 105.454545e-6, 1e-12);
  const double meanVz = (v1 * (-0.02 - 0.03) + v2 * -0.10) / (2 * v1 + v2);
  EXPECT_NEAR(meanVz, -0.0948276, 1e-7);
  const double reMix = 0.804 * std::abs(meanVz) * sauter / 2.444e-5;
  for (std::size_t p = 0; p < 3; ++p) {
    const double d = 2.0 * cell.s.radius[p];
    const double f = drag::yinSundaresan(eps, d / sauter, reMix);
    EXPECT_NEAR(beta[p] / (3.0 * std::numbers::pi * 2.444e-5 * d * f), 1.0, 1e-13) << p;
  }
  // Beetstra polydisperse: the particle's own Re with y = d / <d>
  const std::vector<double> betaB = cell.betas("  drag_law: beetstra_polydisperse\n");
  for (std::size_t p = 0; p < 3; ++p) {
    const double d = 2.0 * cell.s.radius[p];
    const double re = 0.804 * std::abs(cell.s.velocity[p].z) * d / 2.444e-5;
    const double f = drag::beetstraPolydisperse(re, eps, d / sauter);
    EXPECT_NEAR(betaB[p] / (3.0 * std::numbers::pi * 2.444e-5 * d * f), 1.0, 1e-13) << p;
  }
}

TEST(PolydisperseCoupling, FilteredCorrectionScalesTheBeetstraDrag) {
  // beta_filtered / beta = c_corr(alpha) (1 - h(phi) / (L_char / Delta a(phi) + 1)), Delta = 1 mm,
  // L_char from the particles' Sauter mean primary diameter (given here: 40 um) and density.
  PolydisperseCell cell;
  const std::vector<double> plain = cell.betas("  drag_law: beetstra\n  coarse_grain_factor: 2\n");
  const std::vector<double> filtered =
      cell.betas("  drag_law: beetstra\n  coarse_grain_factor: 2\n  drag_correction: filtered\n"
                 "  filtered_drag:\n    primary_diameter: 40e-6\n");
  const double phi = 1.0 - cell.fields.voidFraction(1, 1, 1);
  const double ut = drag::beetstraTerminalVelocity(40e-6, 2250.0, 0.804, 2.444e-5, 9.81);
  const double length = drag::filteredDragLength(ut, 40e-6, 9.81);
  const double expected = drag::parcelDragCorrection(2.0) * drag::filteredDragCorrection(phi, 1e-3, length);
  EXPECT_LT(expected, 0.96);
  for (std::size_t p = 0; p < 3; ++p) EXPECT_NEAR(filtered[p] / plain[p], expected, 1e-13) << p;
}

TEST(PolydisperseCoupling, FluidMediatedFrictionPullsTheClassesTogetherAndConservesMomentum) {
  PolydisperseCell cell;
  auto run = [&](const std::string& extra) {
    auto coupler = makeCoupler("  void_fraction: pcm\n  interpolation: cell\n  drag_law: yin_sundaresan\n" + extra, cell.g);
    dem::ParticleSet copy = cell.s;
    coupler->computeVoidFraction(copy, cell.fields);
    coupler->computeParticleForces(cell.fluid.view(0.804, 2.444e-5), cell.fields, copy);
    return copy.externalForce;
  };
  const auto without = run("");
  const auto with = run("  fluid_mediated_friction: true\n  lubrication_cutoff: 1e-7\n");
  Vec3 sum{};
  std::vector<double> fz;
  for (std::size_t p = 0; p < 3; ++p) {
    const Vec3 friction = with[p] - without[p];
    EXPECT_NEAR(friction.x, 0.0, 1e-30);
    fz.push_back(friction.z);
    sum += friction;
  }
  // class 0 (particles 0, 1; mean v_z -0.025) is pulled down towards class 1 (v_z -0.10), which is held back
  EXPECT_LT(fz[0], 0.0);
  EXPECT_LT(fz[1], 0.0);
  EXPECT_GT(fz[2], 0.0);
  EXPECT_NEAR(fz[0] / fz[1], 1.0, 1e-9);  // same class, same volume: equal shares (to the round-off of with - without)
  EXPECT_NEAR(sum.z / fz[2], 0.0, 1e-9);  // internal to the particles: no momentum to the fluid
  // magnitude: beta_01 (v_1 - v_0) V_cell shared over the class's particles
  const double eps = cell.fields.voidFraction(1, 1, 1), cellVolume = 1e-9, mu = 2.444e-5;
  const double v0 = std::pow(40e-6, 3) * std::numbers::pi / 6, v1 = std::pow(120e-6, 3) * std::numbers::pi / 6;
  const double phi0 = 2 * v0 / cellVolume, phi1 = v1 / cellVolume;
  const double sauter = (2 * v0 + v1) / (2 * v0 / 40e-6 + v1 / 120e-6);
  const double meanVz = (v0 * (-0.02 - 0.03) + v1 * -0.10) / (2 * v0 + v1);
  const double reMix = 0.804 * std::abs(meanVz) * sauter / mu;
  const double beta0 = drag::classFrictionCoefficient(phi0, eps, mu, 40e-6, drag::yinSundaresan(eps, 40e-6 / sauter, reMix) / eps);
  const double beta1 = drag::classFrictionCoefficient(phi1, eps, mu, 120e-6, drag::yinSundaresan(eps, 120e-6 / sauter, reMix) / eps);
  const double beta01 = drag::pairFrictionCoefficient(drag::lubricationFactor(40e-6, 1e-7), phi0, phi1, beta0, beta1);
  EXPECT_NEAR(fz[2] / (beta01 * (-0.025 - -0.10) * cellVolume), 1.0, 1e-9);
  // the keys belong to yin_sundaresan: with another law they are unknown
  EXPECT_THROW(makeCoupler("  drag_law: beetstra\n  fluid_mediated_friction: true\n", cell.g), CaseError);
}

TEST(PolydisperseCoupling, AutoSmoothingLengthIsChosenFromTheParticlesAndPrinted) {
  // 3 parcels of 60 um and 120 um (coarse-graining factor 10: primaries 6 and 12 um) in a 3 mm cube:
  // parcel d32 = (2 * 60^3 + 120^3) / (2 * 60^2 + 120^2) um = 100 um (Tab. 4.15 is per parcel
  // diameter, seed 003 sec. 4.3.1); <phi_p> = (2 V(60 um) + V(120 um)) / 27 mm^3;
  // l = 8.06 d32 (1e-3 / <phi_p>)^(1/3)
  const CartesianGrid g = makeGrid({3, 3, 3}, {1e-3, 1e-3, 1e-3});
  auto coupler = makeCoupler("  smoothing_length: auto\n  coarse_grain_factor: 10\n", g);
  dem::ParticleSet s;
  s.add(0, 0, 30e-6, 2250.0, g.cellCentre(0, 0, 0));
  s.add(1, 0, 30e-6, 2250.0, g.cellCentre(1, 1, 1));
  s.add(2, 0, 60e-6, 2250.0, g.cellCentre(2, 2, 2));
  CouplingFields fields(g);
  std::ostringstream log;
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  coupler->computeVoidFraction(s, fields);
  spdlog::set_default_logger(previous);
  const double phi = (2 * std::pow(60e-6, 3) + std::pow(120e-6, 3)) * std::numbers::pi / 6 / 27e-9;
  EXPECT_NEAR(coupler->settings().smoothingLength / (8.06 * 100e-6 * std::cbrt(1e-3 / phi)), 1.0, 1e-12);
  EXPECT_NE(log.str().find("smoothing_length auto"), std::string::npos) << log.str();
}

TEST(PolydisperseCoupling, OneParticleSizeWarnsThatThePolydisperseLawReducesToMonodisperse) {
  const CartesianGrid g = makeGrid({3, 3, 3}, {1e-3, 1e-3, 1e-3});
  for (const std::string law : {"beetstra_polydisperse", "yin_sundaresan"}) {
    auto coupler = makeCoupler("  drag_law: " + law + "\n", g);
    dem::ParticleSet s = randomParticles(20, 40e-6, 40e-6, {0, 0, 0}, {3e-3, 3e-3, 3e-3});
    FluidFields fluid(g);
    CouplingFields fields(g);
    std::ostringstream log;
    const auto previous = spdlog::default_logger();
    spdlog::set_default_logger(
        std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
    coupler->computeVoidFraction(s, fields);
    coupler->computeParticleForces(fluid.view(0.804, 2.444e-5), fields, s);
    spdlog::set_default_logger(previous);
    EXPECT_NE(log.str().find("drag_law " + law + " with particles of one size"), std::string::npos) << log.str();
    EXPECT_NE(log.str().find("reduces to its monodisperse form"), std::string::npos) << log.str();
    // y = 1 everywhere: the monodisperse form (beetstra_polydisperse: beetstra x (1 + 0.064 eps))
    EXPECT_EQ(coupler->sizeClasses().count(), 1);
  }
}

// Seed 003 Tab. 4.16: the alpha = 33 boxes of the riser's mean cells (parcel d32 = 33 x 6.80 um) got
// l_smooth = 1.77 mm at <phi_p> = 2.22e-3 (3D) and 2.23 mm at 1.11e-3 (2D) from Tab. 4.15 (10.3 at
// alpha 33) and eq. 4.10; the law reproduces both to the table's three digits.
TEST(PolydisperseCoupling, AutoSmoothingLawGivesTheSeedsLargeDomainLengths) {
  const double parcelSauter = 33.0 * 6.80e-6;
  EXPECT_NEAR(autoSmoothingLength(33.0, parcelSauter, 2.22e-3), 1.77e-3, 0.005e-3);
  EXPECT_NEAR(autoSmoothingLength(33.0, parcelSauter, 1.11e-3), 2.23e-3, 0.005e-3);
}
