// Coupler construction from the case file: defaults, documentation mode, errors with names.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/monitor.hpp"
#include "coupling/forces.hpp"
#include "coupling/settling.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

TEST(Coupler, DefaultsWhenSectionIsAbsent) {
  const CartesianGrid g = makeGrid({3, 3, 3}, {0.01, 0.01, 0.01});
  Params p = Params::loadString("other: 1\n", "c.yaml");
  p.real({"other"}, 0.0);
  Coupler c(p, g, {false, false, false}, {0, 0, -9.81});
  p.checkUnknownKeys();
  EXPECT_EQ(c.settings().model, ExchangeModel::A);
  EXPECT_EQ(c.settings().dragLaw, "di_felice");
  EXPECT_EQ(c.settings().voidFraction, "divided");
  EXPECT_EQ(c.settings().exchange, ExchangeScheme::SemiImplicit);
  EXPECT_EQ(c.settings().interpolation, InterpolationMode::Trilinear);
  EXPECT_TRUE(c.settings().forces.drag && c.settings().forces.pressureGradient && c.settings().forces.viscousStress);
  EXPECT_FALSE(c.settings().forces.virtualMass || c.settings().forces.saffmanMeiLift || c.settings().forces.buoyancy);
}

TEST(Coupler, DocumentationModeListsEveryKey) {
  const CartesianGrid g = makeGrid({3, 3, 3}, {0.01, 0.01, 0.01});
  Params p = Params::documentation();
  Coupler c(p, g, {false, false, false}, {0, 0, -9.81});
  std::vector<std::string> paths;
  for (const auto& k : p.documentedKeys()) paths.push_back(k.path);
  for (const char* key : {"coupling.drag_law", "coupling.void_fraction", "coupling.interpolation",
                          "coupling.exchange", "coupling.smoothing_length", "coupling.min_void_fraction",
                          "coupling.coarse_grain_factor",
                          "coupling.kernel_radius_cells", "coupling.samples_per_diameter",
                          "coupling.forces.virtual_mass", "coupling.forces.fluid_torque"})
    EXPECT_NE(std::find(paths.begin(), paths.end(), key), paths.end()) << key;
}

TEST(Coupler, UnknownDragLawNamesTheValidOnes) {
  const CartesianGrid g = makeGrid({3, 3, 3}, {0.01, 0.01, 0.01});
  try {
    makeCoupler("  drag_law: di_feliche\n", g);
    FAIL() << "no error";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.yaml:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("di_felice"), std::string::npos) << msg;
  }
  EXPECT_THROW(makeCoupler("  forces:\n    virtual_mas: true\n", g), CaseError);
  EXPECT_THROW(makeCoupler("  coarse_grain_factor: 0.5\n", g), CaseError);
}

TEST(Coupler, CallOrderIsChecked) {
  const CartesianGrid g = makeGrid({3, 3, 3}, {0.01, 0.01, 0.01});
  auto c = makeCoupler("", g);
  dem::ParticleSet s = randomParticles(5, 0.001, 0.001, {0, 0, 0}, {0.03, 0.03, 0.03});
  FluidFields fluid(g);
  CouplingFields f(g);
  EXPECT_THROW(c->computeParticleForces(fluid.view(1000.0, 1e-3), f, s), std::logic_error);
  EXPECT_THROW(c->fillFluidSources(f), std::logic_error);
}

TEST(Coupler, BalanceMonitorReportsRoundOffErrorAndVolumes) {
  const CartesianGrid g = makeGrid({6, 6, 6}, {0.01, 0.01, 0.01});
  auto c = makeCoupler("  min_void_fraction: 0\n", g);
  dem::ParticleSet s = randomParticles(100, 0.001, 0.002, {0, 0, 0}, {0.06, 0.06, 0.06});
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3& x) { return Vec3{x.y, 0.1, 0.0}; });
  CouplingFields f(g);
  c->computeVoidFraction(s, f);
  c->computeParticleForces(fluid.view(1000.0, 1e-3), f, s);
  c->fillFluidSources(f);
  Params p = Params::loadString("x: 0\n", "m.yaml");
  auto monitor = Registry<Monitor>::instance().createByName("coupling_balance", p);
  RunState state;
  state.coupling = c.get();
  const auto values = monitor->sample(state);
  ASSERT_EQ(values.size(), monitor->columns().size());
  EXPECT_LT(values[3], 1e-13);
  EXPECT_GT(values[4], 0.0);
  EXPECT_NEAR(values[5] / values[4], 1.0, 1e-13);
  EXPECT_EQ(values[6], 0.0);
}

TEST(Coupler, SingleSphereSettlesAtTheLawsTerminalVelocityThroughTheCouplerPath) {
  // Quiescent water with hydrostatic pressure (grad p = rho_f g): model A forces = drag +
  // -V grad p (buoyancy). The particle velocity is integrated with the coupler's force each step
  // (explicit Euler, dt = tau/50) and must reach the law's terminal velocity at the cell's eps
  // (1 - 6.5e-5 in the 2 cm cells) within 0.1 %.
  const CartesianGrid g = makeGrid({3, 3, 3}, {0.02, 0.02, 0.02});
  for (const char* law : {"di_felice", "schiller_naumann", "beetstra"}) {
    auto c = makeCoupler(std::string("  drag_law: ") + law + "\n  void_fraction: pcm\n  interpolation: cell\n", g);
    FluidFields fluid(g);
    fluid.setPressureGradient(g, [](const Vec3&) { return Vec3{0.0, 0.0, -1000.0 * 9.81}; });
    dem::ParticleSet s;
    s.add(0, 0, 0.0005, 2500.0, g.cellCentre(1, 1, 1));
    CouplingFields f(g);
    c->computeVoidFraction(s, f);
    const double vt = terminalVelocity(c->dragLaw(), {1000.0, 1e-3}, 1e-3, 2500.0, 9.81, f.voidFraction(1, 1, 1));
    EXPECT_NEAR(f.voidFraction(1, 1, 1), 1.0 - 6.545e-5, 1e-8);
    const double tau = s.mass[0] / (3.0 * std::numbers::pi * 1e-3 * 1e-3);  // Stokes relaxation time
    const double dt = tau / 50.0;
    for (int n = 0; n < 1500; ++n) {
      c->computeParticleForces(fluid.view(1000.0, 1e-3), f, s);
      s.velocity[0] += dt * (Vec3{0.0, 0.0, -9.81} + s.externalForce[0] / s.mass[0]);
    }
    EXPECT_NEAR(-s.velocity[0].z / vt, 1.0, 1e-3) << law;
    // the fluid gets the drag back (model A), not the buoyancy
    c->fillFluidSources(f);
    EXPECT_EQ(f.forceDensity[2](1, 1, 1), 0.0);  // implicit exchange: drag in K, nothing explicit
    EXPECT_NEAR(f.dragCoefficient(1, 1, 1) * g.cellVolume(), c->dragCoefficients()[0], 1e-20);
  }
}

TEST(Coupler, ExchangeColumnsFollowTheirParticlesThroughReorderingAndRemoval) {
  // The per-particle exchange (beta, slip, other exchanged forces, previous slip) lives in columns
  // of the ParticleSet: a reordering with removals between the force pass and the fluid sources
  // (the DEM's Morton reordering and outlets, ParticleSet::gather) moves each value with its
  // particle, and the fluid receives minus the force of the particles that are left.
  const CartesianGrid g = makeGrid({6, 6, 6}, {0.01, 0.01, 0.01});
  auto c = makeCoupler("  exchange: explicit\n  forces:\n    virtual_mass: true\n    saffman_mei_lift: true\n", g,
                       {false, false, false}, {0, 0, -9.81}, ExchangeModel::B);
  dem::ParticleSet s = randomParticles(300, 0.001, 0.002, {0, 0, 0}, {0.06, 0.06, 0.06});
  FluidFields fluid(g);
  fluid.setVelocity(g, [](const Vec3& x) { return Vec3{x.y, 0.1, -x.x}; });
  fluid.setPressureGradient(g, [](const Vec3& x) { return Vec3{100.0 * x.z, 0.0, 50.0}; });
  CouplingFields f(g);
  c->computeVoidFraction(s, f);
  c->computeParticleForces(fluid.view(1000.0, 1e-3, 1e-3), f, s);
  ASSERT_EQ(c->dragCoefficients().size(), s.size());
  const std::size_t columns[4] = {s.findDoubleColumn(Coupler::kBetaColumn), s.findVec3Column(Coupler::kSlipColumn),
                                  s.findVec3Column(Coupler::kOtherForceColumn),
                                  s.findVec3Column(Coupler::kPreviousSlipColumn)};
  for (std::size_t column : columns) ASSERT_NE(column, dem::ParticleSet::kNoColumn);
  const dem::ParticleSet before = s;
  // reverse the order and drop every third particle
  std::vector<std::uint32_t> order;
  for (std::size_t q = s.size(); q-- > 0;)
    if (q % 3 != 0) order.push_back(static_cast<std::uint32_t>(q));
  s.gather(order);
  ASSERT_EQ(s.size(), 200u);
  Vec3 kept{};
  for (std::size_t p = 0; p < s.size(); ++p) {
    const std::size_t q = order[p];
    ASSERT_EQ(s.id[p], before.id[q]);
    EXPECT_EQ(s.doubleColumns[columns[0]].values[p], before.doubleColumns[columns[0]].values[q]);
    for (int k = 1; k < 4; ++k)
      EXPECT_EQ(s.vec3Columns[columns[k]].values[p], before.vec3Columns[columns[k]].values[q]);
    EXPECT_GT(s.doubleColumns[columns[0]].values[p], 0.0);
    kept += force::drag(s.doubleColumns[columns[0]].values[p], s.vec3Columns[columns[1]].values[p]) +
            s.vec3Columns[columns[2]].values[p];
  }
  // an inserted particle starts with the columns' fill values: it exchanges nothing
  s.add(1000, 0, 0.0015, 2500.0, {0.03, 0.03, 0.03});
  EXPECT_EQ(s.doubleColumns[columns[0]].values.back(), 0.0);
  EXPECT_TRUE(std::isnan(s.vec3Columns[columns[3]].values.back().x));  // no virtual-mass history
  c->computeVoidFraction(s, f);
  c->fillFluidSources(s, f);
  EXPECT_LT(norm(c->momentumBalanceError()), 1e-13 * c->exchangedForceScale());
  Vec3 onFluid{};
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        for (int a = 0; a < 3; ++a) onFluid[a] += f.forceDensity[a](i, j, k) * g.cellVolume();
  EXPECT_LT(norm(onFluid + kept), 1e-12 * c->exchangedForceScale());
}
