// The resolved CFD-DEM cases (cases/resolved_*.yaml) run shortened through `grainflow run`, and
// bad resolved input is refused with the file, line, key and numbers a user needs.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "../app/run_helper.hpp"

namespace gf::resolved {
namespace {

using gf::testing::grainflow;
using gf::testing::readAll;
using gf::testing::TempDir;

std::string source(const std::string& relative) { return std::string(GRAINFLOW_SOURCE_DIR) + "/" + relative; }

/// The last row of a monitor CSV, as numbers.
std::vector<double> lastRow(const std::string& csv) {
  std::istringstream in(readAll(csv));
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') last = line;
  std::vector<double> values;
  std::istringstream row(last);
  std::string cell;
  while (std::getline(row, cell, ',')) values.push_back(std::stod(cell));
  return values;
}

TEST(ResolvedCases, EveryResolvedCaseRunsShortened) {
  // Shortened to a few fluid steps each (end time per case), one thread.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"resolved_cylinder_re100.yaml", "0.02"},
      {"resolved_fixed_sphere.yaml", "0.015"},
      {"resolved_rotating_sphere.yaml", "0.015"},
      {"resolved_stl_cube.yaml", "0.015"},
      {"resolved_settling_sphere.yaml", "0.002"},
      {"resolved_two_spheres_dkt.yaml", "0.003"},
      {"resolved_eight_spheres.yaml", "0.0015"},
      {"resolved_boycott.yaml", "0.002"}};
  int found = 0;
  for (const auto& entry : std::filesystem::directory_iterator(source("cases")))
    found += entry.path().filename().string().rfind("resolved_", 0) == 0;
  EXPECT_EQ(found, static_cast<int>(cases.size())) << "a resolved case without a shortened run here";
  for (const auto& [name, end] : cases) {
    SCOPED_TRACE(name);
    TempDir dir;
    const auto r = grainflow("run " + source("cases/" + name) + " --quiet --threads 1 --end-time " + end + " --output " +
                             dir.file("o"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path() / "o")) {
      if (entry.path().extension() != ".csv") continue;
      const std::vector<double> row = lastRow(entry.path().string());
      ASSERT_FALSE(row.empty()) << entry.path();
      for (double v : row) EXPECT_TRUE(std::isfinite(v)) << entry.path();
    }
  }
}

TEST(ResolvedCases, SettlingSphereStartsDownwardSlowerThanWithoutFluidResistance) {
  // d = 2 mm, 1500 in 1000 kg/m^3: from rest the sphere accelerates at most at (rho_p - rho_f) g /
  // (rho_p + rho_f / 2) = 2.45 m/s^2 (added mass 1/2); the history (Basset) force is of the same
  // size as the inertia after a few ms (12 a^2 rho_f sqrt(pi nu t) against (rho_p + rho_f / 2) 4/3 pi
  // a^3: 0.57 at 5 ms) and the drag grows: after 4 ms the velocity is downward, below the 0.0098 m/s
  // without them and above a quarter of it.
  TempDir dir;
  const auto r = grainflow("run " + source("cases/resolved_settling_sphere.yaml") +
                           " --quiet --threads 1 --end-time 0.004 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::istringstream in(readAll(dir.file("o/particle.csv")));
  std::string line;
  std::vector<double> row;
  while (std::getline(in, line)) {  // the row at t = 0.004 (the monitor samples every 2 ms) and after
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::vector<double> values;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) values.push_back(std::stod(cell));
    row = values;
  }
  ASSERT_GE(row.size(), 7u);  // time, x, y, z, vx, vy, vz, ...
  const double limit = 2.45 * row[0];
  EXPECT_GT(row[0], 0.0039);
  EXPECT_LT(row[6], -0.25 * limit);
  EXPECT_GT(row[6], -limit);
  EXPECT_NEAR(row[4], 0.0, 1e-9);  // (symmetric: no sideways drift)
}

TEST(ResolvedCases, RestartContinuesTheForcesBitForBit) {
  // The fixed body's fluid momentum (rigid-body correction) and the Strouhal monitor's crossings are
  // in the checkpoint: 10 steps in one go and 5 + 5 across a restart write the same last row.
  TempDir dir;
  const std::string file = source("cases/resolved_cylinder_re100.yaml");
  const auto whole = grainflow("run " + file + " --quiet --threads 1 --end-time 0.02 --output " + dir.file("a"));
  ASSERT_EQ(whole.exitCode, 0) << whole.output;
  const auto first = grainflow("run " + file + " --quiet --threads 1 --end-time 0.01 --output " + dir.file("b"));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  const auto second = grainflow("run " + file + " --quiet --threads 1 --end-time 0.02 --output " + dir.file("b") +
                                " --restart " + dir.file("b/checkpoint.bin"));
  ASSERT_EQ(second.exitCode, 0) << second.output;
  const std::vector<double> a = lastRow(dir.file("a/cylinder_forces.csv")), b = lastRow(dir.file("b/cylinder_forces.csv"));
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(a[0], 0.02, 1e-12);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
}

TEST(ResolvedCases, FixedBodyOnFourRanksMatchesOneRank) {
  // The cylinder case cut into 2 x 2 boxes through the cylinder (its centre moved onto the x cut, 0.05
  // cell above the y cut): each rank forces its own cells and the loads are summed over the ranks;
  // the pressure system is gathered onto rank 0's multigrid (fluid/gathered_pressure.hpp), so only
  // the order of the sums over the ranks differs: the forces agree far inside the tolerance.
  if (gf::testing::runShell("command -v mpirun").exitCode != 0) GTEST_SKIP() << "no mpirun";
  TempDir dir;
  std::string text = readAll(source("cases/resolved_cylinder_re100.yaml"));
  text.replace(text.find("centre: [0.4, 0.405, 0.0]"), 25, "centre: [0.8, 0.405, 0.0]");
  const std::string one = dir.write("one.yaml", text);
  text.replace(text.find("  max: [1.6, 0.8, 0.00625]"), 26, "  max: [1.6, 0.8, 0.00625]\n  decomposition: [2, 2, 1]");
  const std::string four = dir.write("four.yaml", text);
  const auto r1 = grainflow("run " + one + " --quiet --threads 1 --end-time 0.02 --output " + dir.file("o1"));
  ASSERT_EQ(r1.exitCode, 0) << r1.output;
  const auto r4 = gf::testing::grainflowOnRanks(4, "run " + four + " --quiet --threads 1 --end-time 0.02 --output " + dir.file("o4"));
  ASSERT_EQ(r4.exitCode, 0) << r4.output;
  const std::vector<double> a = lastRow(dir.file("o1/cylinder_forces.csv")), b = lastRow(dir.file("o4/cylinder_forces.csv"));
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(a[0], 0.02, 1e-12);
  for (std::size_t i = 1; i < 7; ++i) EXPECT_NEAR(a[i], b[i], 1e-7 * std::abs(a[1])) << i;  // forces and torques
  EXPECT_NEAR(a[7], b[7], 1e-7 * a[7]);                                                   // Cd
}

TEST(ResolvedBadInput, ParticlesOnSeveralRanksAreRefused) {
  if (gf::testing::runShell("command -v mpirun").exitCode != 0) GTEST_SKIP() << "no mpirun";
  const auto r = gf::testing::grainflowOnRanks(2, "check " + source("cases/resolved_settling_sphere.yaml"));
  EXPECT_NE(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("resolved particles run on one rank for now"), std::string::npos) << r.output;
}

std::string settlingCaseWith(const std::string& from, const std::string& to) {
  std::string text = readAll(source("cases/resolved_settling_sphere.yaml"));
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(ResolvedBadInput, TooFewCellsPerDiameterIsRefusedWithTheNumbers) {
  TempDir dir;
  // 2 mm spheres on 1 mm cells: 2 cells per diameter.
  const std::string file = dir.write("coarse.yaml", settlingCaseWith("cells: [64, 64, 128]", "cells: [16, 16, 32]"));
  const auto r = grainflow("check " + file);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("coarse.yaml:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fluid.cells"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("diameter 0.002 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cells of 0.001 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at least 4 cells per diameter"), std::string::npos) << r.output;
  // 4 cells per diameter: accepted with a warning naming the 8 recommended.
  const std::string warned = dir.write("warned.yaml", settlingCaseWith("cells: [64, 64, 128]", "cells: [32, 32, 64]"));
  const auto w = grainflow("check " + warned);
  EXPECT_EQ(w.exitCode, 0) << w.output;
  EXPECT_NE(w.output.find("below 8"), std::string::npos) << w.output;
}

TEST(ResolvedBadInput, ParticleOverlappingAFixedBodyIsRefusedWithItsId) {
  TempDir dir;
  const std::string file = dir.write(
      "overlap.yaml",
      settlingCaseWith("resolved: {}",
                       "resolved:\n  bodies:\n    - {shape: sphere, centre: [0.008, 0.008, 0.0225], radius: 0.001}"));
  const auto r = grainflow("check " + file);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("resolved.bodies[0].centre"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle(s) 0 overlapping body 0"), std::string::npos) << r.output;
}

TEST(ResolvedBadInput, ResolvedAndUnresolvedCouplingTogetherAreRefused) {
  TempDir dir;
  const std::string file =
      dir.write("both.yaml", settlingCaseWith("resolved: {}", "resolved: {}\ncoupling: {drag_law: di_felice}"));
  const auto r = grainflow("check " + file);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("both a 'coupling' and a 'resolved' section"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gf::resolved
