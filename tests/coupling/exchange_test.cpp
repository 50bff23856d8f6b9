// Interpolation to particles, distribution back with the void-fraction stencils, Newton's third
// law to round-off, model A / B exchange sets, explicit vs semi-implicit fluid sources.
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "coupling/interpolation.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

namespace {
const CartesianGrid kGrid = makeGrid({8, 7, 9}, {0.01, 0.011, 0.009});
Vec3 swirl(const Vec3& x) {
  return {0.3 + 2.0 * std::sin(40.0 * x.y) * x.z, -0.1 + 5.0 * x.x * x.x, 0.2 * std::cos(30.0 * x.x + 20.0 * x.y)};
}
Vec3 pressureGradient(const Vec3& x) { return {100.0 * x.y, -9810.0 + 50.0 * x.x, 30.0 * std::sin(50.0 * x.z)}; }
}  // namespace

TEST(Interpolation, TrilinearIsExactForLinearFieldsAndCellModeGivesCellValue) {
  const GridTopology topo{kGrid, {false, false, false}};
  Field f(kGrid);
  auto linear = [](const Vec3& x) { return 1.0 + 2.0 * x.x - 3.0 * x.y + 0.5 * x.z; };
  for (int k = 0; k < 9; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 8; ++i) f(i, j, k) = linear(kGrid.cellCentre(i, j, k));
  const Field* const fields[1] = {&f};
  double out[1];
  ParticleStencils none;
  for (Vec3 x : {Vec3{0.031, 0.042, 0.05}, Vec3{0.0051, 0.0071, 0.0046}, Vec3{0.0749, 0.0715, 0.0764}}) {
    sampleAt<InterpolationMode::Trilinear, 1>(topo, none, 0, x, fields, out);
    EXPECT_NEAR(out[0], linear(x), 1e-13);
    sampleAt<InterpolationMode::Cell, 1>(topo, none, 0, x, fields, out);
    const auto c = kGrid.cellOf(x);
    EXPECT_EQ(out[0], f(c[0], c[1], c[2]));
  }
  // within half a cell of a wall the value is held constant (clamped to the first cell centre)
  sampleAt<InterpolationMode::Trilinear, 1>(topo, none, 0, Vec3{0.001, 0.03, 0.03}, fields, out);
  EXPECT_NEAR(out[0], linear(Vec3{0.005, 0.03, 0.03}), 1e-13);
}

TEST(Interpolation, PeriodicTrilinearWrapsAcrossTheBoundary) {
  const GridTopology topo{kGrid, {true, false, false}};
  Field f(kGrid);
  for (int k = 0; k < 9; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 8; ++i) f(i, j, k) = (i == 0 ? 1.0 : (i == 7 ? 3.0 : 0.0));
  const Field* const fields[1] = {&f};
  double out[1];
  ParticleStencils none;
  // x = 0 lies halfway between the centres of cells 7 (image) and 0
  sampleAt<InterpolationMode::Trilinear, 1>(topo, none, 0, Vec3{0.0, 0.03, 0.03}, fields, out);
  EXPECT_NEAR(out[0], 2.0, 1e-13);
}

TEST(Exchange, NewtonsThirdLawHoldsToRoundOffForEveryConfiguration) {
  const dem::ParticleSet base = randomParticles(600, 0.0008, 0.002, {-0.001, -0.001, -0.001}, {0.081, 0.078, 0.082});
  FluidFields fluid(kGrid);
  fluid.setVelocity(kGrid, swirl);
  fluid.setPressureGradient(kGrid, pressureGradient);
  int checked = 0;
  for (const char* scheme : {"pcm", "divided", "kernel", "big_particle"})
    for (const char* interp : {"cell", "trilinear", "stencil"})
      for (const char* model : {"A", "B"})
        for (const char* exchange : {"explicit", "implicit"}) {
          const std::string yaml = std::string("  void_fraction: ") + scheme + "\n  interpolation: " + interp +
                                   "\n  exchange: " + exchange +
                                   "\n  drag_law: beetstra\n  forces:\n    virtual_mass: true\n"
                                   "    saffman_mei_lift: true\n    magnus_lift: true\n    fluid_torque: true\n";
          auto c = makeCoupler(yaml, kGrid, {true, false, false}, {0.0, 0.0, -9.81},
                               std::string(model) == "A" ? ExchangeModel::A : ExchangeModel::B);
          dem::ParticleSet particles = base;
          CouplingFields fields(kGrid);
          c->computeVoidFraction(particles, fields);
          c->computeParticleForces(fluid.view(1.2, 1.8e-5), fields, particles);
          c->fillFluidSources(fields);
          const Vec3 e = c->momentumBalanceError();
          ASSERT_GT(c->exchangedForceScale(), 0.0);
          EXPECT_LT(norm(e), 1e-13 * c->exchangedForceScale()) << scheme << " " << interp << " " << model << " " << exchange;
          ++checked;
        }
  EXPECT_EQ(checked, 48);
}

// Fluid torque on: the particles carry it (hasExternalTorques, non-zero torques in the swirl).
// Off: no torque is written and the stale ones of an earlier pass are cleared, so the DEM force
// loop may skip reading them.
TEST(Exchange, ExternalTorquesAreWrittenOnlyWithFluidTorque) {
  dem::ParticleSet particles = randomParticles(200, 0.001, 0.002, {0, 0, 0}, {0.08, 0.077, 0.081});
  FluidFields fluid(kGrid);
  fluid.setVelocity(kGrid, swirl);
  auto withTorque = makeCoupler("  void_fraction: divided\n  forces:\n    fluid_torque: true\n", kGrid);
  auto without = makeCoupler("  void_fraction: divided\n", kGrid);
  CouplingFields fields(kGrid);
  withTorque->computeVoidFraction(particles, fields);
  withTorque->computeParticleForces(fluid.view(1.2, 1.8e-5), fields, particles);
  EXPECT_TRUE(particles.hasExternalTorques);
  double largest = 0.0;
  for (const Vec3& t : particles.externalTorque) largest = std::max(largest, norm(t));
  EXPECT_GT(largest, 0.0);
  CouplingFields other(kGrid);
  without->computeVoidFraction(particles, other);
  without->computeParticleForces(fluid.view(1.2, 1.8e-5), other, particles);
  EXPECT_FALSE(particles.hasExternalTorques);
  for (const Vec3& t : particles.externalTorque) ASSERT_EQ(t, Vec3{});
  EXPECT_GT(norm(particles.externalForce[0]), 0.0);
}

TEST(Exchange, SemiImplicitFieldsReproduceTheExplicitSourceAtTheCouplingInstant) {
  // u_p per cell is the K-weighted particle velocity corrected by the interpolation defect
  // (u_c - u_f@p), so K (u_c - u_p) equals the explicit drag source in every cell at the coupling
  // instant, for any interpolation; the implicit part only changes how the fluid's new velocity enters.
  const dem::ParticleSet base = randomParticles(300, 0.001, 0.002, {0, 0, 0}, {0.08, 0.077, 0.081});
  FluidFields fluid(kGrid);
  fluid.setVelocity(kGrid, swirl);
  for (const char* interp : {"stencil", "trilinear"}) {
    const std::string common = std::string("  void_fraction: divided\n  interpolation: ") + interp +
                               "\n  forces:\n    pressure_gradient: false\n    viscous_stress: false\n";
    auto ce = makeCoupler(common + "  exchange: explicit\n", kGrid);
    auto ci = makeCoupler(common + "  exchange: implicit\n", kGrid);
    dem::ParticleSet pe = base, pi = base;
    CouplingFields fe(kGrid), fi(kGrid);
    ce->computeVoidFraction(pe, fe);
    ci->computeVoidFraction(pi, fi);
    ce->computeParticleForces(fluid.view(1000.0, 1e-3), fe, pe);
    ci->computeParticleForces(fluid.view(1000.0, 1e-3), fi, pi);
    ce->fillFluidSources(fe);
    ci->fillFluidSources(fi);
    for (std::size_t p = 0; p < base.size(); ++p) EXPECT_EQ(pe.externalForce[p], pi.externalForce[p]);
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 8; ++i) {
          EXPECT_EQ(fi.forceDensity[0](i, j, k), 0.0);  // drag only, all in K
          EXPECT_GE(fi.dragCoefficient(i, j, k), 0.0);
          const double implicitSource =
              -fi.dragCoefficient(i, j, k) * (fluid.u[0](i, j, k) - fi.particleVelocity[0](i, j, k));
          EXPECT_NEAR(implicitSource, fe.forceDensity[0](i, j, k), 1e-9 * (1.0 + std::abs(fe.forceDensity[0](i, j, k))))
              << interp;
        }
  }
}

TEST(Exchange, ModelAKeepsPressureForceOnParticlesOnlyModelBGivesItBack) {
  // Uniform pressure gradient, fluid and particles at rest: only -V_p grad p acts.
  const dem::ParticleSet base = randomParticles(200, 0.001, 0.002, {0, 0, 0}, {0.08, 0.077, 0.081});
  FluidFields fluid(kGrid);
  fluid.setPressureGradient(kGrid, [](const Vec3&) { return Vec3{0.0, 0.0, -9810.0}; });
  double totalVolume = 0.0;
  for (double r : base.radius) totalVolume += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  for (const char* model : {"A", "B"}) {
    dem::ParticleSet particles = base;
    for (auto& v : particles.velocity) v = {};
    auto c = makeCoupler("  exchange: explicit\n", kGrid, {false, false, false}, {0.0, 0.0, -9.81},
                         std::string(model) == "A" ? ExchangeModel::A : ExchangeModel::B);
    CouplingFields fields(kGrid);
    c->computeVoidFraction(particles, fields);
    c->computeParticleForces(fluid.view(1000.0, 1e-3), fields, particles);
    c->fillFluidSources(fields);
    Vec3 onParticles{}, onFluid{};
    for (const Vec3& f : particles.externalForce) onParticles += f;
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 8; ++i) onFluid.z += fields.forceDensity[2](i, j, k) * kGrid.cellVolume();
    EXPECT_NEAR(onParticles.z, 9810.0 * totalVolume, 1e-12 * 9810.0 * totalVolume);  // -V grad p, upwards
    if (std::string(model) == "A")
      EXPECT_EQ(onFluid.z, 0.0);  // the fluid has -eps grad p in its own equation
    else
      EXPECT_NEAR(onFluid.z, -9810.0 * totalVolume, 1e-12 * 9810.0 * totalVolume);
  }
}

TEST(Exchange, DistributionIsTheAdjointOfStencilInterpolation) {
  // sum_p F_p . u(x_p) = sum_c f_c . u_c V_c when u(x_p) uses the same weights as the deposit:
  // the power exchanged is the same seen from the particles and from the fluid.
  const dem::ParticleSet base = randomParticles(300, 0.001, 0.002, {0, 0, 0}, {0.08, 0.077, 0.081});
  FluidFields fluid(kGrid);
  fluid.setVelocity(kGrid, swirl);
  auto c = makeCoupler("  void_fraction: kernel\n  interpolation: stencil\n  exchange: explicit\n"
                       "  forces:\n    pressure_gradient: false\n    viscous_stress: false\n",
                       kGrid);
  dem::ParticleSet particles = base;
  CouplingFields fields(kGrid);
  c->computeVoidFraction(particles, fields);
  c->computeParticleForces(fluid.view(1000.0, 1e-3), fields, particles);
  c->fillFluidSources(fields);
  double particlePower = 0.0, fluidPower = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const ParticleStencils& s = c->stencils();
    Vec3 u{};
    for (int e = 0; e < s.count[p]; ++e)
      for (int a = 0; a < 3; ++a) u[a] += s.weight[p * s.capacity + e] * fluid.u[a].data()[s.cell[p * s.capacity + e]];
    particlePower += dot(particles.externalForce[p], u);
  }
  for (int k = 0; k < 9; ++k)
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 8; ++i)
        for (int a = 0; a < 3; ++a) fluidPower += fields.forceDensity[a](i, j, k) * fluid.u[a](i, j, k) * kGrid.cellVolume();
  EXPECT_NEAR(particlePower, -fluidPower, 1e-12 * std::abs(particlePower));
}

TEST(Exchange, SourcesAfterDemSubstepsFollowParticlesAndKeepTheBalance) {
  // Time-loop order: forces -> DEM substeps (particles move and are reordered) -> void fraction ->
  // fluid sources. The forces computed before the substeps (the coupler's columns of the particle
  // set, moved by ParticleSet::gather) are deposited at the new positions.
  const dem::ParticleSet base = randomParticles(400, 0.001, 0.002, {0, 0, 0}, {0.08, 0.077, 0.081});
  FluidFields fluid(kGrid);
  fluid.setVelocity(kGrid, swirl);
  for (const char* exchange : {"explicit", "implicit"}) {
    auto c = makeCoupler(std::string("  exchange: ") + exchange + "\n", kGrid, {true, false, false}, {0.0, 0.0, -9.81},
                         ExchangeModel::B);
    dem::ParticleSet particles = base;
    CouplingFields fields(kGrid);
    c->computeVoidFraction(particles, fields);
    c->computeParticleForces(fluid.view(1.2, 1.8e-5), fields, particles);
    Vec3 total{};
    for (std::size_t p = 0; p < particles.size(); ++p) total += particles.externalForce[p];
    // "DEM": reverse the order and move every particle by 3 mm in x (wrapping periodically)
    dem::ParticleSet moved = particles;
    std::vector<std::uint32_t> order(particles.size());
    for (std::size_t q = 0; q < order.size(); ++q) order[q] = static_cast<std::uint32_t>(particles.size() - 1 - q);
    moved.gather(order);
    for (Vec3& x : moved.position) {
      x += Vec3{0.003, 0.0, 0.0};
      if (x.x >= 0.08) x.x -= 0.08;
    }
    c->computeVoidFraction(moved, fields);
    c->fillFluidSources(moved, fields);
    EXPECT_LT(norm(c->momentumBalanceError()), 1e-13 * c->exchangedForceScale()) << exchange;
    // the fluid receives minus the total force computed before the substeps
    Vec3 onFluid{};
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 8; ++i)
          for (int a = 0; a < 3; ++a)
            onFluid[a] += (fields.forceDensity[a](i, j, k) -
                           fields.dragCoefficient(i, j, k) * (fluid.u[a](i, j, k) - fields.particleVelocity[a](i, j, k))) *
                          kGrid.cellVolume();
    EXPECT_LT(norm(onFluid + total), 1e-12 * c->exchangedForceScale()) << exchange;
  }
}

TEST(Exchange, StencilsOfAFusedDepositAreRebuiltWhenAnUnfusedDepositNeedsThem) {
  // After the time-loop order (forces -> move -> void fraction with the exchange fused -> sources)
  // the divided stencils were built piece by piece and not kept (trilinear forces read none):
  // stencils() says so, and a later unfused exchange (forces again, sources) rebuilds them from
  // the particles it is given: the same fields as a coupler that recomputed the void fraction.
  const dem::ParticleSet base = randomParticles(5000, 0.001, 0.0015, {0, 0, 0}, {0.08, 0.077, 0.081}, 17);
  FluidFields fluid(kGrid);
  fluid.setVelocity(kGrid, swirl);
  std::vector<Field> results[2];
  for (int variant = 0; variant < 2; ++variant) {
    auto c = makeCoupler("  void_fraction: divided\n  interpolation: trilinear\n", kGrid);
    dem::ParticleSet particles = base;
    CouplingFields fields(kGrid);
    c->computeVoidFraction(particles, fields);
    EXPECT_NO_THROW(c->stencils());  // (nothing pending: an unfused deposit keeps them)
    c->computeParticleForces(fluid.view(1.2, 1.8e-5), fields, particles);
    for (std::size_t p = 0; p < particles.size(); ++p) particles.position[p].z += 0.0004;  // "DEM"
    c->computeVoidFraction(particles, fields);
    EXPECT_THROW(c->stencils(), std::logic_error);
    c->fillFluidSources(particles, fields);
    if (variant == 1) {
      c->computeVoidFraction(particles, fields);  // (nothing pending: kept)
      EXPECT_NO_THROW(c->stencils());
    }
    c->computeParticleForces(fluid.view(1.2, 1.8e-5), fields, particles);
    if (variant == 0) {
      EXPECT_THROW(c->fillFluidSources(fields), std::logic_error);  // (no particles to rebuild from)
    }
    c->fillFluidSources(particles, fields);
    EXPECT_LT(norm(c->momentumBalanceError()), 1e-13 * c->exchangedForceScale());
    results[variant] = {fields.forceDensity[0],     fields.forceDensity[1],     fields.forceDensity[2],
                        fields.dragCoefficient,     fields.particleVelocity[0], fields.particleVelocity[1],
                        fields.particleVelocity[2], fields.voidFraction};
  }
  for (std::size_t f = 0; f < results[0].size(); ++f) EXPECT_EQ(results[0][f].data(), results[1][f].data()) << "field " << f;
}

TEST(Exchange, FullCouplingStepIsBitIdenticalForTheSameThreadCount) {
  // 5000 particles: the parallel paths (stencils, sampling, deposit with per-thread buffers) run.
  const CartesianGrid g = makeGrid({12, 12, 12}, {0.01, 0.01, 0.01});
  const dem::ParticleSet base = randomParticles(5000, 0.0005, 0.001, {0, 0, 0}, {0.12, 0.12, 0.12}, 5);
  FluidFields fluid(g);
  fluid.setVelocity(g, swirl);
  fluid.setPressureGradient(g, pressureGradient);
  for (const char* scheme : {"divided", "kernel"}) {
    const std::string yaml = std::string("  void_fraction: ") + scheme +
                             "\n  smoothing_length: 0.01\n  smooth_exchange_fields: true\n"
                             "  forces:\n    saffman_mei_lift: true\n";
    dem::ParticleSet p1 = base, p2 = base;
    CouplingFields f1(g), f2(g);
    auto c1 = makeCoupler(yaml, g), c2 = makeCoupler(yaml, g);
    for (auto [c, p, f] : {std::tuple{c1.get(), &p1, &f1}, std::tuple{c2.get(), &p2, &f2}}) {
      c->computeVoidFraction(*p, *f);
      c->computeParticleForces(fluid.view(1.2, 1.8e-5), *f, *p);
      c->fillFluidSources(*p, *f);
    }
    EXPECT_EQ(p1.externalForce, p2.externalForce) << scheme;
    EXPECT_EQ(f1.voidFraction.data(), f2.voidFraction.data()) << scheme;
    EXPECT_EQ(f1.dragCoefficient.data(), f2.dragCoefficient.data()) << scheme;
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(f1.forceDensity[a].data(), f2.forceDensity[a].data()) << scheme;
      EXPECT_EQ(f1.particleVelocity[a].data(), f2.particleVelocity[a].data()) << scheme;
    }
  }
}

TEST(Exchange, ParticleForcesAreTheSameOnOneTwoAndThreeThreads) {
  // Trilinear sampling on several threads packs, per thread, the cell planes its particles read
  // (Coupler::forcePass): the forces must equal those of the single pack on one thread bit for
  // bit. Particles sorted by height, so every thread's block reads other planes; the default
  // forces (drag, pressure gradient, viscous stress) and all of them with lifts.
  const CartesianGrid g = makeGrid({6, 8, 20}, {0.01, 0.01, 0.01});
  dem::ParticleSet base = randomParticles(6000, 0.0004, 0.0008, {0, 0, 0}, {0.06, 0.08, 0.2}, 11);
  std::vector<std::size_t> order(base.size());
  for (std::size_t q = 0; q < order.size(); ++q) order[q] = q;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return base.position[a].z < base.position[b].z; });
  dem::ParticleSet sorted;
  for (std::size_t q : order)
    sorted.add(base.id[q], 0, base.radius[q], 2500.0, base.position[q], base.velocity[q], base.angularVelocity[q]);
  FluidFields fluid(g);
  fluid.setVelocity(g, swirl);
  fluid.setPressureGradient(g, pressureGradient);
  const int saved = omp_get_max_threads();
  for (const char* forces : {"", "  forces:\n    saffman_mei_lift: true\n    magnus_lift: true\n"}) {
    std::vector<Vec3> reference;
    for (int threads : {1, 2, 3}) {
      omp_set_num_threads(threads);
      dem::ParticleSet p = sorted;
      CouplingFields f(g);
      auto c = makeCoupler(std::string("  void_fraction: divided\n") + forces, g);
      c->computeVoidFraction(p, f);
      c->computeParticleForces(fluid.view(1.2, 1.8e-5), f, p);
      if (threads == 1) reference = p.externalForce;
      else EXPECT_EQ(p.externalForce, reference) << threads << " threads " << forces;
    }
  }
  omp_set_num_threads(saved);
}

TEST(Exchange, AnUnevenParticleSplitIsReplacedByEqualBlocks) {
  // Coupler::setParticleBlocks keeps the DEM's split only while no block holds more than 5 %
  // above an equal share (the coupling's passes cost the same per particle). The deposits add
  // the threads' sums in thread order, so the split shows in the last bits of the void fraction:
  // an uneven split must give the bits of equal blocks, a nearly equal one its own.
  EXPECT_TRUE(Coupler::nearlyEqual({0, 3000, 6000}));
  EXPECT_TRUE(Coupler::nearlyEqual({0, 3150, 6000}));
  EXPECT_FALSE(Coupler::nearlyEqual({0, 3151, 6000}));
  EXPECT_FALSE(Coupler::nearlyEqual({0, 2000, 6000}));  // (the other block is the large one)
  EXPECT_FALSE(Coupler::nearlyEqual({}));
  const CartesianGrid g = makeGrid({6, 8, 20}, {0.01, 0.01, 0.01});
  // (solid fraction ~0.4: the regrouped sums' last bits survive eps = 1 - solid fraction)
  const dem::ParticleSet base = randomParticles(6000, 0.0018, 0.0026, {0, 0, 0}, {0.06, 0.08, 0.2}, 11);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(2);
  auto voidFraction = [&](const std::vector<std::size_t>& blocks) {
    CouplingFields f(g);
    auto c = makeCoupler("  void_fraction: divided\n", g);
    c->setParticleBlocks(blocks);
    c->computeVoidFraction(base, f);
    return f.voidFraction.data();
  };
  const std::vector<double> equal = voidFraction({});
  EXPECT_EQ(voidFraction({0, 4200, 6000}), equal);  // 70 % in one block: replaced
  EXPECT_EQ(voidFraction({0, 3000, 6000}), equal);  // the equal split itself
  // kept: 3100 / 2900 moves 100 particles' sums into the other buffer (a change in the last bits
  // somewhere; the same volume to round-off)
  const std::vector<double> kept = voidFraction({0, 3100, 6000});
  EXPECT_NE(kept, equal);
  for (std::size_t q = 0; q < kept.size(); ++q) EXPECT_NEAR(kept[q], equal[q], 1e-13);
  omp_set_num_threads(saved);
}

TEST(Exchange, SubstepAverageGivesTheFluidTheMeanExchangeOfTheSubstepsPerParticle) {
  // substep_fluid_fields: interpolated. Forces before each of two substeps (different fluid
  // states; the "DEM" reverses the particle order in between): the fluid receives, cell by cell,
  // the mean of what each substep's forces alone would give, and the balance holds.
  const dem::ParticleSet base = randomParticles(400, 0.001, 0.002, {0, 0, 0}, {0.08, 0.077, 0.081});
  FluidFields first(kGrid), second(kGrid);
  first.setVelocity(kGrid, swirl);
  first.setPressureGradient(kGrid, pressureGradient);
  second.setVelocity(kGrid, [](const Vec3& x) { return 0.5 * swirl(x) + Vec3{0.1, -0.2, 0.3}; });
  second.setPressureGradient(kGrid, [](const Vec3& x) { return 0.7 * pressureGradient(x); });
  dem::ParticleSet reversed;
  for (std::size_t q = base.size(); q-- > 0;)
    reversed.add(base.id[q], 0, base.radius[q], 2500.0, base.position[q], base.velocity[q], base.angularVelocity[q]);
  // per interior cell and axis: the exchange the fluid sees, forceDensity - K (u_c - u_p)
  auto exchangeOf = [](const CouplingFields& f, const FluidFields& at) {
    std::vector<double> e;
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 8; ++i)
          for (int a = 0; a < 3; ++a)
            e.push_back(f.forceDensity[a](i, j, k) -
                        f.dragCoefficient(i, j, k) * (at.u[a](i, j, k) - f.particleVelocity[a](i, j, k)));
    return e;
  };
  for (const char* exchange : {"explicit", "implicit"}) {
    const std::string yaml = std::string("  exchange: ") + exchange + "\n  substep_fluid_fields: interpolated\n";
    auto single = [&](const FluidFields& fluid, const dem::ParticleSet& set) {
      auto c = makeCoupler(yaml, kGrid, {true, false, false}, {0.0, 0.0, -9.81}, ExchangeModel::B);
      dem::ParticleSet p = set;
      CouplingFields fields(kGrid);
      c->computeVoidFraction(p, fields);
      c->computeParticleForces(fluid.view(1.2, 1.8e-5), fields, p);
      c->computeVoidFraction(p, fields);
      c->fillFluidSources(p, fields);
      return std::pair{exchangeOf(fields, fluid), fields.dragCoefficient};
    };
    const auto [e1, k1] = single(first, base);
    const auto [e2, k2] = single(second, reversed);

    auto c = makeCoupler(yaml, kGrid, {true, false, false}, {0.0, 0.0, -9.81}, ExchangeModel::B);
    dem::ParticleSet particles = base;
    CouplingFields fields(kGrid);
    c->computeVoidFraction(particles, fields);
    c->beginSubstepAverage();
    c->computeParticleForces(first.view(1.2, 1.8e-5), fields, particles);
    std::vector<std::uint32_t> order(particles.size());  // the "DEM": base -> reversed
    for (std::size_t q = 0; q < order.size(); ++q) order[q] = static_cast<std::uint32_t>(particles.size() - 1 - q);
    particles.gather(order);
    ASSERT_EQ(particles.position, reversed.position);
    c->computeParticleForces(second.view(1.2, 1.8e-5), fields, particles);
    c->endSubstepAverage(particles);
    c->computeVoidFraction(particles, fields);
    c->fillFluidSources(particles, fields);
    EXPECT_LT(norm(c->momentumBalanceError()), 1e-13 * c->exchangedForceScale()) << exchange;
    const std::vector<double> mean = exchangeOf(fields, second);
    double scale = 0.0;
    for (double v : e1) scale = std::max(scale, std::abs(v));
    ASSERT_GT(scale, 0.0);
    for (std::size_t q = 0; q < mean.size(); ++q)
      ASSERT_NEAR(mean[q], 0.5 * (e1[q] + e2[q]), 1e-12 * scale) << exchange << " entry " << q;
    for (int k = 0; k < 9; ++k)
      for (int j = 0; j < 7; ++j)
        for (int i = 0; i < 8; ++i)
          EXPECT_NEAR(fields.dragCoefficient(i, j, k), 0.5 * (k1(i, j, k) + k2(i, j, k)),
                      1e-12 * std::max(1.0, std::abs(k1(i, j, k))));
  }
}

TEST(Exchange, SubstepFieldsInterpolatedRejectStencilInterpolation) {
  EXPECT_THROW(makeCoupler("  interpolation: stencil\n  substep_fluid_fields: interpolated\n", kGrid), CaseError);
}
