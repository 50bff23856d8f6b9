// Coupled CFD-DEM example cases run end to end through the command line.
#include <gtest/gtest.h>

#include <cmath>

#include "io/csv_series.hpp"
#include "run_helper.hpp"

using gf::testing::grainflow;
using gf::testing::TempDir;

// Seed 001 (Lethe CFD-DEM paper), sec. 3.1 and Table 2: a 2 mm glass bead (2500 kg/m^3) settling
// in water (997 kg/m^3, nu = 1.005e-6 m^2/s) with Di Felice drag reaches 0.2328 m/s.
TEST(CoupledCases, SingleParticleSettlingReachesPublishedTerminalVelocity) {
  TempDir dir;
  const auto r = grainflow("run " + gf::testing::sourcePath("cases/single_particle_settling.yaml") +
                           " --quiet --threads 1 --end-time 0.3 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto csv = gf::io::readCsv(dir.file("o/particle_probe.csv"));
  ASSERT_EQ(csv.header.at(6), "vz [m/s]");
  const double terminal = -csv.rows.back().at(6);
  EXPECT_NEAR(terminal, 0.2328, 0.02 * 0.2328) << "2 % of the published value";
  // It accelerates monotonically towards it (no overshoot beyond 1 %).
  double fastest = 0.0;
  for (const auto& row : csv.rows) fastest = std::max(fastest, -row.at(6));
  EXPECT_LT(fastest, 1.01 * terminal);
  // The fluid output exists as a ParaView series.
  EXPECT_NE(gf::testing::readAll(dir.file("o/fluid.pvd")).find("fluid_000006.vti"), std::string::npos);
}
