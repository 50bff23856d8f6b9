// Void-fraction schemes: exact conservation of particle volume (walls, periodic boundaries,
// particles reaching over walls), expected eps for regular lattices, big particles, lower bound.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

namespace {

const char* kSchemes[] = {"pcm", "divided", "kernel", "big_particle"};

std::string schemeYaml(const std::string& scheme, double minEps = 0.0) {
  return "  void_fraction: " + scheme + "\n  min_void_fraction: " + std::to_string(minEps) + "\n";
}

}  // namespace

TEST(VoidFraction, ConservesParticleVolumeWithWallsAndPeriodicBoundaries) {
  const CartesianGrid g = makeGrid({8, 6, 10}, {0.01, 0.012, 0.01});
  // centres up to one radius outside the box: kernels and satellite points reach over every face
  const dem::ParticleSet particles = randomParticles(400, 0.001, 0.004, {-0.004, -0.004, -0.004}, {0.084, 0.076, 0.104});
  for (const char* scheme : kSchemes) {
    for (std::array<bool, 3> periodic : {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true},
                                         std::array<bool, 3>{true, true, true}}) {
      auto coupler = makeCoupler(schemeYaml(scheme), g, periodic);
      CouplingFields fields(g);
      coupler->computeVoidFraction(particles, fields);
      const double exact = coupler->particleVolume();
      EXPECT_NEAR(solidVolume(fields.voidFraction) / exact, 1.0, 1e-12) << scheme;
      EXPECT_NEAR(coupler->depositedVolume() / exact, 1.0, 1e-13) << scheme;
      EXPECT_EQ(coupler->clippedVolume(), 0.0);
    }
  }
}

TEST(VoidFraction, ConservesVolumeWithManyThreadsBitIdenticallyAcrossRuns) {
  const CartesianGrid g = makeGrid({10, 10, 10}, {0.01, 0.01, 0.01});
  const dem::ParticleSet particles = randomParticles(5000, 0.001, 0.002, {0, 0, 0}, {0.1, 0.1, 0.1}, 11);
  for (const char* scheme : kSchemes) {
    auto coupler = makeCoupler(schemeYaml(scheme), g);
    CouplingFields a(g), b(g);
    coupler->computeVoidFraction(particles, a);
    coupler->computeVoidFraction(particles, b);
    EXPECT_EQ(a.voidFraction.data(), b.voidFraction.data()) << scheme;
    EXPECT_NEAR(solidVolume(a.voidFraction) / coupler->particleVolume(), 1.0, 1e-12) << scheme;
  }
}

TEST(VoidFraction, RegularLatticeGivesUniformExpectedVoidFraction) {
  // One particle of radius r at every cell centre: eps = 1 - (4/3 pi r^3) / dx^3 in every cell, for
  // every scheme (kernel: by symmetry of the lattice, walls mirror it onto itself).
  const double dx = 0.01, r = 0.003;
  const CartesianGrid g = makeGrid({6, 5, 7}, {dx, dx, dx});
  dem::ParticleSet particles;
  int id = 0;
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) particles.add(id++, 0, r, 2500.0, g.cellCentre(i, j, k));
  const double expected = 1.0 - 4.0 / 3.0 * std::numbers::pi * r * r * r / (dx * dx * dx);  // 0.886903
  for (const char* scheme : kSchemes) {
    for (bool periodic : {false, true}) {
      auto coupler = makeCoupler(schemeYaml(scheme), g, {periodic, periodic, periodic});
      CouplingFields fields(g);
      coupler->computeVoidFraction(particles, fields);
      for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 5; ++j)
          for (int i = 0; i < 6; ++i) ASSERT_NEAR(fields.voidFraction(i, j, k), expected, 1e-12) << scheme;
    }
  }
}

TEST(VoidFraction, ShiftedPeriodicLatticeIsUniformForSmoothSchemes) {
  // Particles on the cell corners (shifted lattice) of a fully periodic box: the smooth schemes
  // spread each volume over several cells, the lattice sum is still uniform.
  const double dx = 0.01, r = 0.004;
  const CartesianGrid g = makeGrid({5, 5, 5}, {dx, dx, dx});
  dem::ParticleSet particles;
  int id = 0;
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) particles.add(id++, 0, r, 2500.0, Vec3{i * dx + 0.3 * dx, j * dx, k * dx});
  const double expected = 1.0 - 4.0 / 3.0 * std::numbers::pi * r * r * r / (dx * dx * dx);
  for (const char* scheme : kSchemes) {
    auto coupler = makeCoupler(schemeYaml(scheme), g, {true, true, true});
    CouplingFields fields(g);
    coupler->computeVoidFraction(particles, fields);
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) ASSERT_NEAR(fields.voidFraction(i, j, k), expected, 1e-12) << scheme;
  }
}

TEST(VoidFraction, KernelSpreadsBeyondTheCellAndDividedStaysWithinTheSphere) {
  const double dx = 0.01;
  const CartesianGrid g = makeGrid({9, 9, 9}, {dx, dx, dx});
  dem::ParticleSet one;
  one.add(0, 0, 0.004, 2500.0, g.cellCentre(4, 4, 4));
  {  // kernel radius 2.2 cells: the neighbours of the centre cell receive volume
    auto c = makeCoupler("  void_fraction: kernel\n  kernel_radius_cells: 2.2\n  min_void_fraction: 0\n", g);
    CouplingFields f(g);
    c->computeVoidFraction(one, f);
    EXPECT_LT(f.voidFraction(5, 4, 4), 1.0);
    EXPECT_LT(f.voidFraction(6, 4, 4), 1.0);
    EXPECT_EQ(f.voidFraction(7, 4, 4), 1.0);  // beyond 2.2 cells
    EXPECT_LT(f.voidFraction(4, 4, 4), f.voidFraction(5, 4, 4));
    EXPECT_EQ(c->stencils().count[0], 125);  // tensor-product support: offsets -2..2 per axis
  }
  {  // divided: a particle with r = 0.8 dx at a cell corner puts 1/29 of its volume at each point
    dem::ParticleSet corner;
    corner.add(0, 0, 0.008, 2500.0, Vec3{0.04, 0.04, 0.04});
    auto c = makeCoupler(schemeYaml("divided"), g);
    CouplingFields f(g);
    c->computeVoidFraction(corner, f);
    double solid = 0.0;
    int touched = 0;
    for (int k = 2; k < 7; ++k)
      for (int j = 2; j < 7; ++j)
        for (int i = 2; i < 7; ++i)
          if (f.voidFraction(i, j, k) < 1.0) {
            ++touched;
            solid += (1.0 - f.voidFraction(i, j, k)) * g.cellVolume();
            // each cell's share is a multiple of V_p / 29
            const double parts = (1.0 - f.voidFraction(i, j, k)) * g.cellVolume() / (c->particleVolume() / 29.0);
            EXPECT_NEAR(parts, std::round(parts), 1e-9);
          }
    EXPECT_EQ(touched, 8);
    EXPECT_NEAR(solid / c->particleVolume(), 1.0, 1e-12);
  }
}

TEST(VoidFraction, BigParticleSpreadsOverOverlappedCells) {
  // Sphere of radius 2.5 dx centred in a cell: the centre cell and its 6 face neighbours lie
  // entirely inside (farthest corner at sqrt(1.5^2 + 0.5^2 + 0.5^2) dx = 1.66 dx < r).
  const double dx = 0.01, r = 0.025;
  const CartesianGrid g = makeGrid({11, 11, 11}, {dx, dx, dx});
  dem::ParticleSet big;
  big.add(0, 0, r, 2500.0, g.cellCentre(5, 5, 5));
  auto c = makeCoupler("  void_fraction: big_particle\n  samples_per_diameter: 40\n  min_void_fraction: 0\n", g);
  CouplingFields f(g);
  c->computeVoidFraction(big, f);
  // fully covered cells: solid fraction 1 up to the sampling error of the sphere volume (~1 %)
  EXPECT_NEAR(f.voidFraction(5, 5, 5), 0.0, 0.02);
  EXPECT_NEAR(f.voidFraction(6, 5, 5), 0.0, 0.02);
  EXPECT_NEAR(f.voidFraction(5, 4, 5), 0.0, 0.02);
  // cells far outside untouched; total volume exact
  EXPECT_EQ(f.voidFraction(5, 5, 9), 1.0);
  EXPECT_EQ(f.voidFraction(8, 8, 8), 1.0);  // corner distance > r
  EXPECT_NEAR(solidVolume(f.voidFraction) / c->particleVolume(), 1.0, 1e-12);
  // PCM would have put V_p = 65 V_c into one cell: eps = 1 - 65.4 < 0 -> clipped
  auto pcm = makeCoupler(schemeYaml("pcm", 0.1), g);
  CouplingFields fp(g);
  pcm->computeVoidFraction(big, fp);
  EXPECT_EQ(fp.voidFraction(5, 5, 5), 0.1);
  EXPECT_NEAR(pcm->clippedVolume(), c->particleVolume() - 0.9 * g.cellVolume(), 1e-15);
}

TEST(VoidFraction, LowerBoundAndOldFieldAndGhosts) {
  const double dx = 0.01;
  const CartesianGrid g = makeGrid({4, 4, 4}, {dx, dx, dx});
  dem::ParticleSet dense;
  for (int n = 0; n < 6; ++n) dense.add(n, 0, 0.004, 2500.0, g.cellCentre(0, 0, 0));  // 6 x 0.268 V_c
  auto c = makeCoupler(schemeYaml("pcm", 0.3), g, {true, false, false});
  CouplingFields f(g);
  c->computeVoidFraction(dense, f);
  EXPECT_EQ(f.voidFraction(0, 0, 0), 0.3);
  const double raw = 1.0 - 6.0 * 4.0 / 3.0 * std::numbers::pi * 0.004 * 0.004 * 0.004 / (dx * dx * dx);
  EXPECT_NEAR(c->clippedVolume(), (0.3 - raw) * g.cellVolume(), 1e-18);
  EXPECT_EQ(f.voidFractionOld(0, 0, 0), 1.0);
  c->computeVoidFraction(dense, f);
  EXPECT_EQ(f.voidFractionOld(0, 0, 0), 0.3);
  // ghosts: periodic in x (wrap), walls in y and z (copy of the neighbour)
  EXPECT_EQ(f.voidFraction(4, 0, 0), f.voidFraction(0, 0, 0));
  EXPECT_EQ(f.voidFraction(-1, 0, 0), f.voidFraction(3, 0, 0));
  EXPECT_EQ(f.voidFraction(0, -1, 0), f.voidFraction(0, 0, 0));
  EXPECT_EQ(f.voidFraction(0, 0, -2), f.voidFraction(0, 0, 0));
}
