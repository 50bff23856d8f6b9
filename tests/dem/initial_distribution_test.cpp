// random_packing's initial_distribution (seed 003 sec. 4.2, Tab. 4.10-4.11): bisected puts three
// times the solid concentration in the lower half normal to split_axis, quadrisectioned three times
// in two diagonal quarters; the region's mean concentration is kept; homogeneous is the plain fill.
#include <gtest/gtest.h>

#include <array>
#include <numbers>

#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

std::string boxCase(const std::string& layout, const std::string& size = "{distribution: constant, diameter: 2.0e-4}") {
  return R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01], periodic: [1, 1, 1]}
materials:
  - {name: a, density: 2250, youngs_modulus: 5.0e7, poisson_ratio: 0.45}
insertion:
  - type: random_packing
    material: a
    min: [0, 0, 0]
    max: [0.01, 0.01, 0.01]
    volume_fraction: 0.01
    size: )" + size + "\n    initial_distribution: " + layout + "\n    split_axis: x\n    second_split_axis: z\n    seed: 5\n";
}

/// Solid volume in each quarter (x below/above the middle, z below/above), m^3.
std::array<double, 4> quarterVolumes(const ParticleSet& p) {
  std::array<double, 4> v{};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int a = p.position[i].x >= 0.005, b = p.position[i].z >= 0.005;
    v[a + 2 * b] += 4.0 / 3.0 * std::numbers::pi * p.radius[i] * p.radius[i] * p.radius[i];
  }
  return v;
}

TEST(InitialDistribution, BisectedHoldsThreeTimesTheConcentrationInTheLowerHalf) {
  test::DemCase c(boxCase("bisected"), {0, 0, -9.81});
  const auto v = quarterVolumes(c->particles());
  const double lower = v[0] + v[2], upper = v[1] + v[3], total = lower + upper;
  EXPECT_NEAR(total, 0.01 * 1e-6, 0.01 * 0.01 * 1e-6);  // the region's mean concentration
  // monodisperse: the dealing keeps 3:1 to one particle (V = 4.2e-12 m^3 of 1e-8)
  EXPECT_NEAR(lower / upper, 3.0, 0.01);
}

TEST(InitialDistribution, QuadrisectionedHoldsThreeTimesTheConcentrationInTwoDiagonalQuarters) {
  test::DemCase c(boxCase("quadrisectioned", "{distribution: discrete, diameters: [1.0e-4, 2.0e-4, 3.0e-4], "
                                              "mass_fractions: [0.5, 0.3, 0.2]}"),
                  {0, 0, -9.81});
  const auto v = quarterVolumes(c->particles());
  const double sparse = 0.5 * (v[1] + v[2]);
  // dense quarters: (lower x, lower z) and (upper x, upper z); within the largest sphere's volume
  const double largest = std::numbers::pi / 6.0 * 27e-12;
  EXPECT_NEAR(v[0], 3.0 * sparse, 3.0 * largest);
  EXPECT_NEAR(v[3], 3.0 * sparse, 3.0 * largest);
  EXPECT_NEAR(v[1], v[2], largest);
}

TEST(InitialDistribution, HomogeneousFillsTheQuartersEvenly) {
  test::DemCase c(boxCase("homogeneous"), {0, 0, -9.81});
  const auto v = quarterVolumes(c->particles());
  const double mean = 0.25 * (v[0] + v[1] + v[2] + v[3]);
  for (double q : v) EXPECT_NEAR(q / mean, 1.0, 0.1);  // ~600 spheres per quarter: 4 % noise
}

TEST(InitialDistribution, SameAxisTwiceIsRejected) {
  std::string text = boxCase("quadrisectioned");
  text.replace(text.find("second_split_axis: z"), 20, "second_split_axis: x");
  EXPECT_THROW(test::DemCase(text, {0, 0, -9.81}), CaseError);
}

}  // namespace
}  // namespace gf::dem
