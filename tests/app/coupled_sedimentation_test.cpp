// Liquid-solid batch sedimentation (cases/cfddem_batch_sedimentation.yaml), first 0.4 s: a random
// suspension (eps = 0.8) in a closed column settles as a block at the hindered settling velocity.
#include <gtest/gtest.h>

#include "io/csv_series.hpp"
#include "run_helper.hpp"

using gf::testing::grainflow;
using gf::testing::TempDir;

// Reference: Richardson & Zaki v_t eps^n at eps = 0.8 = 2.4349 mm/s (v_t = 6.854 mm/s of the Dallavalle
// drag, n = 4.638 of Rowe 1987; validation/cfddem_hindered_settling/make_reference.py). A random
// suspension on cells of 3 d with smoothing (l = 3 d) and a sediment forming at the bottom: within
// 20 % (the lattice suspension of validation/cfddem_hindered_settling is within 2 %). Single-sphere
// settling (v_t) would be 2.8 times faster. Every exchange conserves momentum to round-off.
TEST(CoupledSedimentation, SuspensionSettlesAtTheHinderedVelocity) {
  TempDir dir;
  const auto r = grainflow("run " + gf::testing::sourcePath("cases/cfddem_batch_sedimentation.yaml") +
                           " --quiet --threads 1 --end-time 0.4 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto csv = gf::io::readCsv(dir.file("o/suspension_settling.csv"));
  ASSERT_EQ(csv.header.at(4), "hindered_settling_velocity [m/s]");
  double sum = 0.0;
  int n = 0;
  for (const auto& row : csv.rows)
    if (row.at(0) >= 0.1 - 1e-9) {
      sum += row.at(4);
      ++n;
    }
  ASSERT_GT(n, 20);
  EXPECT_NEAR(sum / n, 2.4349e-3, 0.20 * 2.4349e-3);
  const auto balance = gf::io::readCsv(dir.file("o/coupling_balance.csv"));
  for (const auto& row : balance.rows) EXPECT_LT(row.at(4), 1e-12);
}
