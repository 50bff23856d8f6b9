// Monitor CSVs while a run goes: rows reach disk every run.progress_interval of wall time (not only
// with a checkpoint), and a restart from an earlier checkpoint gives the uninterrupted run's rows.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <thread>

#include "io/csv_series.hpp"
#include "run_helper.hpp"

using gf::testing::BackgroundGrainflow;
using gf::testing::grainflow;
using gf::testing::readAll;
using gf::testing::TempDir;

namespace {
// 64 spheres falling onto a floor; monitors every 2 ms of simulated time.
const std::string kCase = R"(case: {name: monitor_files}
domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.06]}
time: {end: 0.04, dem_step: 2.0e-5}
materials: [{name: glass, density: 2500.0, youngs_modulus: 5.0e6, restitution: 0.5}]
walls: [{type: plane, point: [0, 0, 0], normal: [0, 0, 1]}]
insertion:
  - {type: lattice, material: glass, origin: [0.004, 0.004, 0.004], spacing: 0.0043, nx: 4, ny: 4, nz: 4,
     diameter: 0.004, velocity: [0.01, -0.02, -0.1]}
monitors:
  - {type: particle_count, interval: 0.002}
  - {type: kinetic_energy, interval: 0.002}
)";

std::size_t dataRows(const std::string& csv) {
  if (!std::filesystem::exists(csv)) return 0;
  return gf::io::readCsv(csv).rows.size();
}
}  // namespace

TEST(MonitorFiles, RowsReachDiskWhileTheRunGoes) {
  // A run far longer than the test, quiet, no checkpoint before the end: the CSV must still grow.
  TempDir dir;
  std::string text = kCase;
  text.replace(text.find("end: 0.04"), 9, "end: 1000.0");
  text.replace(text.find("velocity: [0.01, -0.02, -0.1]"), 29, "velocity: [0.0, 0.0, -0.1]");  // (stays inside)
  text += "run: {progress_interval: 0.2}\n";
  const std::string file = dir.write("case.yaml", text);
  const std::string csv = dir.file("o/kinetic_energy.csv");
  BackgroundGrainflow run({"run", file, "--quiet", "--threads", "1", "--output", dir.file("o")}, dir.file("log.txt"));
  ASSERT_TRUE(run.started());

  // Rows beyond the first (t = 0) ones, on disk, while the process still runs.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::size_t rowsSeen = 0;
  while (run.running() && std::chrono::steady_clock::now() < deadline) {
    rowsSeen = dataRows(csv);
    if (rowsSeen >= 3) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(run.running()) << "the run ended early (exit " << run.wait() << "):\n" << readAll(dir.file("log.txt"));
  ASSERT_GE(rowsSeen, 3u) << "no monitor rows on disk after 60 s of a running run";
  EXPECT_FALSE(std::filesystem::exists(dir.file("o/checkpoint.bin"))) << "rows came with a checkpoint";
  EXPECT_GE(dataRows(dir.file("o/particle_count.csv")), 1u);
  const gf::io::CsvTable during = gf::io::readCsv(csv);
  EXPECT_EQ(during.header.size(), 3u);  // time and the two energies, each with its unit

  // SIGTERM: checkpoint, exit 130; the rows seen while it ran are the first rows of the final file.
  run.signal(SIGTERM);
  EXPECT_EQ(run.wait(), 130) << readAll(dir.file("log.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir.file("o/checkpoint.bin")));
  const gf::io::CsvTable after = gf::io::readCsv(csv);
  ASSERT_GE(after.rows.size(), during.rows.size());
  for (std::size_t r = 0; r < during.rows.size(); ++r) EXPECT_EQ(after.rows[r], during.rows[r]) << "row " << r;
}

TEST(MonitorFiles, RestartFromAnEarlierCheckpointGivesTheUninterruptedRows) {
  // A run that died at t = 0.03 with its last checkpoint at t = 0.017 has CSV rows on disk beyond
  // that checkpoint. Restarted from it, it must write exactly the rows of an uninterrupted run.
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCase);
  const std::string args = " --quiet --threads 2 --output ";
  const auto full = grainflow("run " + file + args + dir.file("full"));
  ASSERT_EQ(full.exitCode, 0) << full.output;

  const auto first = grainflow("run " + file + args + dir.file("split") + " --end-time 0.017");
  ASSERT_EQ(first.exitCode, 0) << first.output;
  std::filesystem::copy_file(dir.file("split/checkpoint.bin"), dir.file("checkpoint_0.017.bin"));
  const auto ahead = grainflow("run " + file + args + dir.file("split") + " --end-time 0.03 --restart " +
                               dir.file("split/checkpoint.bin"));
  ASSERT_EQ(ahead.exitCode, 0) << ahead.output;
  ASSERT_NEAR(gf::io::readCsv(dir.file("split/kinetic_energy.csv")).rows.back().at(0), 0.03, 1e-9);  // rows past 0.017

  const auto resumed = grainflow("run " + file + args + dir.file("split") + " --restart " + dir.file("checkpoint_0.017.bin"));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
  for (const char* name : {"kinetic_energy.csv", "particle_count.csv"}) {
    EXPECT_GT(dataRows(dir.file(std::string("full/") + name)), 15u) << name;
    EXPECT_EQ(readAll(dir.file(std::string("full/") + name)), readAll(dir.file(std::string("split/") + name))) << name;
  }
}
