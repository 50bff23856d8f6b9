// Coupled CFD-DEM bed cases run through the command line (shortened variants of cases/ and
// validation/cfddem_* items; the full runs and their numbers are in docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "io/csv_series.hpp"
#include "run_helper.hpp"

using gf::testing::grainflow;
using gf::testing::TempDir;

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Ergun (1952), seed 001 eq. 35: pressure drop of a bed of height Hb.
double ergun(double U, double eps, double d, double Hb, double mu, double rho) {
  return 150.0 * std::pow(1 - eps, 2) * mu * U * Hb / (std::pow(eps, 3) * d * d) +
         1.75 * (1 - eps) * rho * U * U * Hb / (std::pow(eps, 3) * d);
}

}  // namespace

// cases/cfddem_fixed_packed_bed.yaml: fixed simple-cubic bed (eps = 1 - pi/6, d = 2 mm, Hb = 32 mm, water), Gidaspow drag: the pressure
// gradient inside the bed times Hb is Ergun's pressure drop within 5 % at Re_p = 40, and
// Newton's third law of the exchange holds to round-off in every coupling step.
TEST(CoupledBeds, FixedPackedBedFollowsErgun) {
  TempDir dir;
  std::string text = gf::testing::readAll(gf::testing::sourcePath("cases/cfddem_fixed_packed_bed.yaml"));
  text = replaced(text, "velocity: [0.0, 0.0, 0.01]", "velocity: [0.0, 0.0, 0.02]");
  text += "  - type: coupling_balance\n    interval: 0.001\n";
  const auto r = grainflow("run " + dir.write("bed.yaml", text) + " --quiet --threads 1 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto dp = gf::io::readCsv(dir.file("o/pressure_drop.csv"));
  const double gradient = dp.rows.back().at(1) / dp.rows.back().at(2);
  const double expected = ergun(0.02, 1.0 - std::numbers::pi / 6.0, 0.002, 0.032, 1e-3, 1000.0);
  EXPECT_NEAR(gradient * 0.032, expected, 0.05 * expected);
  EXPECT_NEAR(dp.rows.back().at(3), 0.02, 1e-9) << "superficial velocity below the bed";
  const auto balance = gf::io::readCsv(dir.file("o/coupling_balance.csv"));
  ASSERT_GT(balance.rows.size(), 10u);
  for (const auto& row : balance.rows) EXPECT_LT(row.at(4), 1e-12) << "relative momentum error at t = " << row.at(0);
}

// Pseudo-2D bubbling bed (cases/cfddem_bubbling_fluidised_bed.yaml, 24,750 spheres), first 4 ms: the inlet ramps up, the loose
// packing starts to fall (mean centre height decreases), every exchange conserves momentum to
// round-off and the particle volume is deposited completely; the pressure drop is positive and below
// the weight per area of the bed (the bed is not yet carried by the gas).
TEST(CoupledBeds, BubblingBedStartsConsistently) {
  TempDir dir;
  std::string text = gf::testing::readAll(gf::testing::sourcePath("cases/cfddem_bubbling_fluidised_bed.yaml"));
  text += "  - type: fluid_max_divergence\n    interval: 0.0002\n";
  const auto r = grainflow("run " + dir.write("bed.yaml", text) + " --quiet --threads 1 --end-time 0.004 --output " +
                           dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // Continuity of the fluid step just made, d eps/dt + div(eps u) = 0, with the eps pair that step
  // used (the coupler has already computed the next one when the monitor samples): the pressure
  // solve's tolerance, far below the void-fraction rates of the bed (|d eps/dt| up to ~10^2 1/s,
  // which a mixed-up pair shows instead).
  const auto divergence = gf::io::readCsv(dir.file("o/fluid_max_divergence.csv"));
  ASSERT_GE(divergence.rows.size(), 10u);
  for (const auto& row : divergence.rows) EXPECT_LT(row.at(1), 1e-3) << "max |div| [1/s] at t = " << row.at(0);
  const auto height = gf::io::readCsv(dir.file("o/bed_height.csv"));
  EXPECT_LT(height.rows.back().at(2), height.rows.front().at(2));
  const auto balance = gf::io::readCsv(dir.file("o/coupling_balance.csv"));
  for (const auto& row : balance.rows) {
    EXPECT_LT(row.at(4), 1e-12);
    EXPECT_NEAR(row.at(6), row.at(5), 1e-12 * row.at(5)) << "deposited = particle volume";
  }
  // Weight per area: 24750 x pi/6 (2.5 mm)^3 x (2526 - 1.2) kg/m^3 x 9.81 / (0.015 x 0.15 m^2).
  const double weight = 24750 * std::numbers::pi / 6 * std::pow(0.0025, 3) * 2524.8 * 9.81 / (0.015 * 0.15);
  const auto dp = gf::io::readCsv(dir.file("o/pressure_drop.csv"));
  EXPECT_GT(dp.rows.back().at(1), 0.0);
  EXPECT_LT(dp.rows.back().at(1), weight);
  // The inlet cells are free of particles (distributor above them): the superficial velocity
  // entering the bed is the ramped inlet velocity, 1.875 m/s x 4 ms / 0.3 s.
  EXPECT_NEAR(dp.rows.back().at(3), 1.875 * 0.004 / 0.3, 1e-9);
}

// Spouted bed of seed 001 (Table 5) with 5000 instead of 175,800 spheres, first 20 ms: the inlet acts
// only through the open channel (blocked cells beside it), so the superficial velocity in the bed
// is 20.8 m/s x 24 / 280; the jet accelerates spheres beyond what gravity and collisions can give
// them (speeds <= g t = 0.196 m/s for spheres released at rest), and the exchange conserves
// momentum to round-off.
TEST(CoupledBeds, SpoutedBedJetLiftsParticles) {
  TempDir dir;
  std::string text = gf::testing::readAll(gf::testing::sourcePath("cases/cfddem_spouted_bed.yaml"));
  text = replaced(text, "count: 175800", "count: 5000");
  text = replaced(text, "max: [0.28, 0.04, 0.64]", "max: [0.28, 0.04, 0.2]");
  const auto r = grainflow("run " + dir.write("spout.yaml", text) + " --quiet --threads 1 --end-time 0.02 --output " +
                           dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto dp = gf::io::readCsv(dir.file("o/pressure_drop.csv"));
  EXPECT_NEAR(dp.rows.back().at(3), 20.8 * 0.024 / 0.28, 1e-6);
  const auto stats = gf::io::readCsv(dir.file("o/particle_statistics.csv"));
  ASSERT_EQ(stats.header.at(8), "speed_max [m/s]");
  EXPECT_GT(stats.rows.back().at(8), 1.5 * 9.81 * 0.02);
  const auto balance = gf::io::readCsv(dir.file("o/coupling_balance.csv"));
  for (const auto& row : balance.rows) EXPECT_LT(row.at(4), 1e-12);
}

// Convergence with the smoothing length (coupling.smoothing_length = l): the whole-domain pressure
// drop of the fixed bed (its total drag, set by eps and the drag law) tends to the unsmoothed value as
// l -> 0 at second order while l << dx (the implicit diffusion step changes a cell field by
// l^2 laplace(eps) + O(l^4)): observed order from l = 0.25 and 0.5 mm on 4 mm cells within
// 1.8 ... 2.2, and the change is monotonic (smoothing only lowers the drag at the bed ends).
TEST(CoupledBeds, PressureDropConvergesWithSmoothingLength) {
  TempDir dir;
  const std::string base =
      gf::testing::readAll(gf::testing::sourcePath("cases/cfddem_fixed_packed_bed.yaml"));
  auto dropWith = [&](const std::string& l) {
    std::string text = replaced(base, "  interpolation: cell", "  smoothing_length: " + l + "\n  interpolation: cell");
    text = replaced(text, "    lower: 0.021", "    lower: 0.001");
    text = replaced(text, "    upper: 0.043", "    upper: 0.063");
    const std::string out = dir.file("o" + l);
    const auto r = grainflow("run " + dir.write("bed" + l + ".yaml", text) + " --quiet --threads 1 --output " + out);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return gf::io::readCsv(out + "/pressure_drop.csv").rows.back().at(1);
  };
  const double p0 = dropWith("0"), p1 = dropWith("0.00025"), p2 = dropWith("0.0005");
  ASSERT_GT(p0 - p1, 0.0);
  ASSERT_GT(p1 - p2, 0.0);
  const double order = std::log2((p0 - p2) / (p0 - p1));
  EXPECT_GT(order, 1.8);
  EXPECT_LT(order, 2.2);
}

// Tank drain of seed 002 (single-phase approximation, constant head H = 0.35 m) with 8 of the 41
// particle layers, first 0.1 s: water leaves through the 24.4 x 25 mm tap hole only (the blocked
// tank wall around it), at a rate below Torricelli's bound a^2 sqrt(2 g H); the spheres stay behind
// the particle grid, and the exchange conserves momentum to round-off.
TEST(CoupledBeds, TankDrainsThroughTheTapHole) {
  TempDir dir;
  std::string text = gf::testing::readAll(gf::testing::sourcePath("cases/cfddem_tank_drain_constant_head.yaml"));
  text = replaced(text, "nz: 41", "nz: 8");
  const auto r = grainflow("run " + dir.write("tank.yaml", text) + " --quiet --threads 1 --end-time 0.1 --output " +
                           dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto dp = gf::io::readCsv(dir.file("o/pressure_drop.csv"));
  const double outflow = dp.rows.back().at(3) * 0.15 * 0.35;  // m^3/s through the plane x = 0.3178 m
  const double torricelli = 0.0244 * 0.025 * std::sqrt(2.0 * 9.81 * 0.35);
  EXPECT_GT(outflow, 0.2 * torricelli);
  EXPECT_LT(outflow, torricelli);
  const auto stats = gf::io::readCsv(dir.file("o/particle_statistics.csv"));
  EXPECT_EQ(stats.rows.back().at(1), 44 * 22 * 8);
  EXPECT_GE(stats.rows.back().at(2), 0.0);
  const auto balance = gf::io::readCsv(dir.file("o/coupling_balance.csv"));
  for (const auto& row : balance.rows) EXPECT_LT(row.at(4), 1e-12);
}

// Rayleigh-Taylor suspension of seed 001 sec. 3.3 (A = 0.286 column), first 0.03 s: the monitor's
// Atwood number from the measured layer solid fraction and the densities matches seed 001 eq. 43
// (rho_mix = 0.912 x 1 + 0.088 x 10 = 1.792 kg/m^3, A = 0.284) within 2 %; the layer is still sharp
// (width within 3 cell layers of the 50 mm suspension: the exponential phase has just begun); the
// exchange conserves momentum to round-off. The growth coefficient alpha is validated in
// validation/cfddem_rayleigh_taylor.
TEST(CoupledBeds, RayleighTaylorLayerStartsSharpWithSeedAtwoodNumber) {
  TempDir dir;
  const auto r = grainflow("run " + gf::testing::sourcePath("cases/cfddem_rayleigh_taylor.yaml") +
                           " --quiet --threads 1 --end-time 0.03 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto layer = gf::io::readCsv(dir.file("o/mixing_layer.csv"));
  ASSERT_EQ(layer.header.at(4), "atwood_number [-]");
  const double rhoMix = 0.912 * 1.0 + 0.088 * 10.0;
  EXPECT_NEAR(layer.rows.back().at(4), (rhoMix - 1.0) / (rhoMix + 1.0), 0.02 * 0.284);
  EXPECT_LT(layer.rows.back().at(1), 3 * 0.15 / 128);
  const auto balance = gf::io::readCsv(dir.file("o/coupling_balance.csv"));
  for (const auto& row : balance.rows) EXPECT_LT(row.at(4), 1e-12);
}
