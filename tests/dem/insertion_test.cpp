// Insertion methods, size distributions and outlets.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "dem/insertion/size_distribution.hpp"
#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

using test::DemCase;
using test::materialsYaml;

std::unique_ptr<SizeDistribution> distribution(const std::string& yaml) {
  Params p = Params::loadString(yaml, "size.yaml");
  return readSizeDistribution(p);
}

double volume(double d) { return std::numbers::pi / 6.0 * d * d * d; }

TEST(DemInsertion, DiscreteDistributionReproducesMassFractions) {
  auto dist = distribution("size: {distribution: discrete, diameters: [0.001, 0.002], mass_fractions: [0.3, 0.7]}");
  Random rng(1);
  double small = 0.0, total = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double d = dist->sample(rng);
    total += volume(d);
    if (d < 0.0015) small += volume(d);
  }
  EXPECT_NEAR(small / total, 0.3, 0.01);  // statistical error ~0.003
}

TEST(DemInsertion, LogNormalMedianAndRosinRammlerD63) {
  auto logNormal = distribution("size: {distribution: log_normal, median_diameter: 0.002, sigma: 0.2}");
  Random rng(2);
  std::vector<double> d(100001);
  for (double& x : d) x = logNormal->sample(rng);
  std::nth_element(d.begin(), d.begin() + 50000, d.end());
  EXPECT_NEAR(d[50000], 0.002, 0.002 * 0.01);
  // Rosin-Rammler by mass: with wide truncation the mass fraction finer than d63 is 1 - 1/e.
  auto rr = distribution(
      "size: {distribution: rosin_rammler, characteristic_diameter: 0.002, spread: 4, min_diameter: 0.0008, "
      "max_diameter: 0.004}");
  double fine = 0.0, total = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double x = rr->sample(rng);
    total += volume(x);
    if (x < 0.002) fine += volume(x);
  }
  const double fMin = 1 - std::exp(-std::pow(0.4, 4)), fMax = 1 - std::exp(-std::pow(2.0, 4));
  EXPECT_NEAR(fine / total, (1 - std::exp(-1.0) - fMin) / (fMax - fMin), 0.01);
}

// minDiameter() bounds every sample from below and is reached (within 2 % for the continuous
// distributions' truncation); a discrete diameter with mass fraction 0 is never drawn, so it is
// not the minimum.
TEST(DemInsertion, SmallestDiameterBoundsTheSamples) {
  const std::vector<std::pair<std::string, double>> cases = {
      {"size: {distribution: constant, diameter: 0.003}", 0.003},
      {"size: {distribution: discrete, diameters: [0.001, 0.002, 0.004], mass_fractions: [0, 0.5, 0.5]}", 0.002},
      {"size: {distribution: discrete, diameters: [0.004, 0.001], mass_fractions: [1, 0]}", 0.004},
      {"size: {distribution: log_normal, median_diameter: 0.002, sigma: 0.3, min_diameter: 0.0015}", 0.0015},
      {"size: {distribution: rosin_rammler, characteristic_diameter: 0.002, spread: 3}", 0.001}};
  for (const auto& [yaml, expected] : cases) {
    auto dist = distribution(yaml);
    EXPECT_DOUBLE_EQ(dist->minDiameter(), expected) << yaml;
    Random rng(4);
    double smallest = 1.0;
    for (int k = 0; k < 20000; ++k) smallest = std::min(smallest, dist->sample(rng));
    EXPECT_GE(smallest, dist->minDiameter()) << yaml;
    EXPECT_LT(smallest, 1.02 * dist->minDiameter()) << yaml;
  }
}

TEST(DemInsertion, SameSeedSameParticles) {
  auto a = distribution("size: {distribution: log_normal, median_diameter: 0.002, sigma: 0.2}");
  Random r1(9), r2(9);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(a->sample(r1), a->sample(r2));
}

TEST(DemInsertion, RandomPackingReachesVolumeFractionWithoutOverlaps) {
  DemCase c(materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}
insertion:
  - {type: random_packing, min: [0, 0, 0], max: [0.02, 0.02, 0.02], volume_fraction: 0.25, seed: 4,
     size: {distribution: discrete, diameters: [0.0015, 0.002], mass_fractions: [0.5, 0.5]}}
)",
            {0, 0, 0});
  const ParticleSet& p = c->particles();
  double solid = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    solid += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3);
    for (std::size_t j = i + 1; j < p.size(); ++j)
      ASSERT_GE(norm(p.position[i] - p.position[j]), p.radius[i] + p.radius[j]);
  }
  EXPECT_NEAR(solid / 8e-6, 0.25, 0.01);
  EXPECT_EQ(c->contactStatistics().particleContacts, 0);
}

// Above the random-sequential-addition range (~0.3) random_packing uses a jittered FCC lattice:
// the requested fraction is reached (to one particle), nothing overlaps, all inside the region.
TEST(DemInsertion, RandomPackingReachesHighVolumeFractionOnJitteredLattice) {
  const std::pair<double, const char*> cases[] = {
      {0.45, "{distribution: discrete, diameters: [0.0018, 0.002], mass_fractions: [0.5, 0.5]}"},
      {0.6, "{diameter: 0.002}"}};
  for (const auto& [fraction, size] : cases) {
    DemCase c(materialsYaml("hertz_mindlin", 0.5, 0.5) + fmt::format(R"(
domain: {{min: [0, 0, 0], max: [0.02, 0.02, 0.03]}}
insertion:
  - {{type: random_packing, min: [0, 0, 0], max: [0.02, 0.02, 0.03], volume_fraction: {}, seed: 4,
     size: {}}}
)",
                                                                      fraction, size),
              {0, 0, 0});
    const ParticleSet& p = c->particles();
    double solid = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      solid += 4.0 / 3.0 * std::numbers::pi * std::pow(p.radius[i], 3);
      for (int a = 0; a < 3; ++a) {
        ASSERT_GE(p.position[i][a] - p.radius[i], -1e-12);
        ASSERT_LE(p.position[i][a] + p.radius[i], (a == 2 ? 0.03 : 0.02) + 1e-12);
      }
    }
    EXPECT_NEAR(solid / 1.2e-5, fraction, 0.005);
    EXPECT_EQ(c->contactStatistics().particleContacts, 0);  // no pair within r_i + r_j
    // Not a perfect lattice: the positions are jittered.
    double spread = 0.0;
    for (std::size_t i = 1; i < p.size(); ++i) spread += std::abs(p.position[i].x - p.position[0].x);
    EXPECT_GT(spread, 0.0);
  }
}

TEST(DemInsertion, RateInsertionDeliversMassFlowAndOutletCountsRemovedMass) {
  DemCase c(materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [0, 0, -0.1], max: [0.02, 0.02, 0.05]}
insertion:
  - {type: rate, corner: [0.001, 0.001, 0.04], edge_a: [0.018, 0, 0], edge_b: [0, 0.018, 0],
     mass_flow_rate: 0.01, velocity: [0, 0, -1], start: 0.0, end: 0.05, seed: 3, size: {diameter: 0.002}}
outlets:
  - {name: sink, min: [0, 0, -0.1], max: [0.02, 0.02, -0.05]}
)",
            {0, 0, -9.81});
  const double dt = 1e-5, particleMass = 2500 * volume(0.002);
  while (c->time() < 0.05 - 0.5 * dt) c->step(dt);
  const double inserted = static_cast<double>(c->particles().size()) * particleMass;
  EXPECT_NEAR(inserted, 0.01 * 0.05, particleMass);  // within one particle
  while (c->time() < 0.3) c->step(dt);                // all fall into the sink
  EXPECT_EQ(c->particles().size(), 0u);
  EXPECT_NEAR(c->outlets()[0].removedMass, inserted, 1e-12);
}

TEST(DemInsertion, CsvFileAndLattice) {
  const auto dir = std::filesystem::temp_directory_path() / "grainflow_dem_csv";
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "p.csv");
    f << "x,y,z,r,vx,vy,vz\n0.01,0.01,0.01,0.001,0,0,-1\n0.01,0.01,0.02,0.0015,0,0,0\n";
  }
  const std::string yaml = materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [0, 0, 0], max: [0.03, 0.03, 0.03]}
insertion:
  - {type: csv_file, file: p.csv}
  - {type: lattice, origin: [0.005, 0.005, 0.025], spacing: 0.0025, nx: 3, ny: 2, nz: 1, diameter: 0.002}
)";
  Params params = Params::loadString(yaml, (dir / "case.yaml").string());
  const Domain domain = Domain::read(params);
  System s(params, domain, {0, 0, 0});
  ASSERT_EQ(s.particles().size(), 8u);
  // Morton reordering may change the order: find by id.
  for (std::size_t i = 0; i < s.particles().size(); ++i) {
    if (s.particles().id[i] == 0) {
      EXPECT_EQ(s.particles().velocity[i], (Vec3{0, 0, -1}));
    }
    if (s.particles().id[i] == 1) {
      EXPECT_DOUBLE_EQ(s.particles().radius[i], 0.0015);
    }
    if (s.particles().id[i] >= 2) {
      EXPECT_DOUBLE_EQ(s.particles().radius[i], 0.001);
    }
  }
}

TEST(DemInsertion, UnknownMaterialNamesTheValidOnes) {
  EXPECT_THROW(
      {
        try {
          DemCase c(materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [0, 0, 0], max: [0.03, 0.03, 0.03]}
insertion:
  - {type: lattice, material: glas, origin: [0.01, 0.01, 0.01], spacing: 0.003, diameter: 0.002}
)",
                    {0, 0, 0});
        } catch (const CaseError& e) {
          EXPECT_NE(std::string(e.what()).find("glass"), std::string::npos);
          throw;
        }
      },
      CaseError);
}

}  // namespace
}  // namespace gf::dem
