// End-to-end behaviour of `grainflow run`: restart equals continuous, divergence handling,
// interruption with checkpoint, output layout.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "io/csv_series.hpp"
#include "io/vtk.hpp"
#include "run_helper.hpp"

using gf::testing::grainflow;
using gf::testing::readAll;
using gf::testing::TempDir;

namespace {
const std::string kCase = R"(case: {name: restart}
domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.06]}
time: {end: 0.04, dem_step: 2.0e-5}
materials: [{name: glass, density: 2500.0, youngs_modulus: 5.0e6, restitution: 0.5}]
walls: [{type: plane, point: [0, 0, 0], normal: [0, 0, 1]}]
insertion:
  - {type: lattice, material: glass, origin: [0.004, 0.004, 0.004], spacing: 0.0043, nx: 4, ny: 4, nz: 4,
     diameter: 0.004, velocity: [0.01, -0.02, -0.1]}
output: {interval: 0.005}
monitors: [{type: particle_count, interval: 0.002}]
)";
}

namespace {
/// Runs `file` on 2 threads to its end in dir/full, and in dir/split to `splitTime`, then on
/// from that checkpoint to the end.
void runWholeAndRestarted(const TempDir& dir, const std::string& file, const std::string& splitTime) {
  const auto full = grainflow("run " + file + " --quiet --threads 2 --output " + dir.file("full"));
  ASSERT_EQ(full.exitCode, 0) << full.output;
  const auto first = grainflow("run " + file + " --quiet --threads 2 --end-time " + splitTime + " --output " + dir.file("split"));
  ASSERT_EQ(first.exitCode, 0) << first.output;
  const auto resumed = grainflow("run " + file + " --quiet --threads 2 --output " + dir.file("split") + " --restart " +
                                 dir.file("split/checkpoint.bin"));
  ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
}
}  // namespace

TEST(Run, RestartEqualsContinuousBitForBit) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCase);
  runWholeAndRestarted(dir, file, "0.017");
  if (HasFatalFailure()) return;
  // Final states (positions, velocities, forces, counters) are identical byte for byte.
  const std::string full = readAll(dir.file("full/checkpoint.bin"));
  EXPECT_GT(full.size(), 1000u);
  EXPECT_EQ(full, readAll(dir.file("split/checkpoint.bin")));
  EXPECT_EQ(readAll(dir.file("full/particles_000008.vtu")), readAll(dir.file("split/particles_000008.vtu")));
  // Series and monitors continue without gaps or duplicates.
  EXPECT_EQ(readAll(dir.file("full/particles.pvd")), readAll(dir.file("split/particles.pvd")));
  EXPECT_EQ(readAll(dir.file("full/particle_count.csv")), readAll(dir.file("split/particle_count.csv")));
}

namespace {
// A small fluidised column (5,040 spheres: above the particle count from which the coupling's
// particle loops run on a team), for the coupled restart.
const std::string kCoupledCase = R"(case: {name: coupled_restart}
domain: {min: [0, 0, 0], max: [0.01, 0.035, 0.1]}
time: {end: 0.008, dem_step: 4.0e-6, coupling_interval: 5}
materials: [{name: glass, density: 2526.0, youngs_modulus: 1.0e8, poisson_ratio: 0.35}]
contact: {law: hertz_mindlin, restitution: 0.9, friction: 0.1}
walls: [{type: box, min: [0, 0, 0], max: [0.01, 0.035, 0.1], open: [0, 0, 0, 0, 1, 1]},
        {type: plane, point: [0, 0, 0.005], normal: [0, 0, 1]}]
insertion:
  - {type: lattice, material: glass, origin: [0.001, 0.0012, 0.0062], spacing: 0.0016, nx: 6, ny: 20, nz: 42,
     diameter: 0.0015, velocity: [0.0, 0.0, -0.05]}
fluid:
  density: 1.2
  viscosity: 1.8e-5
  cells: [2, 7, 20]
  boundaries:
    x_min: {type: slip}
    x_max: {type: slip}
    y_min: {type: wall}
    y_max: {type: wall}
    z_min: {type: inlet, velocity: [0.0, 0.0, 1.5]}
    z_max: {type: pressure_outlet}
coupling: {drag_law: gidaspow, void_fraction: divided}
monitors: [{type: coupling_balance, interval: 0.001}]
)";
}  // namespace

TEST(Run, CoupledRestartEqualsContinuousBitForBit) {
  // Fluid, coupling and DEM state after a restart on 2 threads equal the continuous run's (the
  // coupling's particle loops follow the DEM's split of the particles, a function of the lists).
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCoupledCase);
  runWholeAndRestarted(dir, file, "0.0036");
  if (HasFatalFailure()) return;
  const std::string a = readAll(dir.file("full/checkpoint.bin"));
  EXPECT_GT(a.size(), 100000u);
  EXPECT_EQ(a, readAll(dir.file("split/checkpoint.bin")));
  EXPECT_EQ(readAll(dir.file("full/coupling_balance.csv")), readAll(dir.file("split/coupling_balance.csv")));
}

TEST(Run, SameInputSameThreadsSameResult) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCase);
  ASSERT_EQ(grainflow("run " + file + " --quiet --threads 2 --end-time 0.01 --output " + dir.file("a")).exitCode, 0);
  ASSERT_EQ(grainflow("run " + file + " --quiet --threads 2 --end-time 0.01 --output " + dir.file("b")).exitCode, 0);
  EXPECT_EQ(readAll(dir.file("a/checkpoint.bin")), readAll(dir.file("b/checkpoint.bin")));
}

TEST(Run, ReportsNeighbourListBuildsOfTheRun) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCase);
  ASSERT_EQ(grainflow("run " + file + " --quiet --end-time 0.02 --output " + dir.file("o")).exitCode, 0);
  // The continued run reports its own steps (0.02 s -> 0.04 s at 2e-5 s: 1000), not the total.
  const auto r = grainflow("run " + file + " --output " + dir.file("o") + " --restart " + dir.file("o/checkpoint.bin"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::size_t at = r.output.find("neighbour lists");
  ASSERT_NE(at, std::string::npos) << r.output;
  long long builds = -1, steps = -1;
  ASSERT_EQ(std::sscanf(r.output.c_str() + at, "neighbour lists %lld builds in %lld DEM steps", &builds, &steps), 2);
  EXPECT_EQ(steps, 1000);
  // The lattice falls at >= 0.1 m/s: 2 mm in 0.02 s, five skins (0.1 d = 0.4 mm), so the lists
  // are rebuilt, but far from every step.
  EXPECT_GE(builds, 3);
  EXPECT_LT(builds, 200);
}

TEST(Run, WritesParaViewSeriesWithPhysicalTimes) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCase);
  const auto r = grainflow("run " + file + " --threads 1 --end-time 0.01 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("paraview"), std::string::npos);
  EXPECT_NE(r.output.find("neighbour search"), std::string::npos) << "timing table missing";
  const std::string pvd = readAll(dir.file("o/particles.pvd"));
  EXPECT_NE(pvd.find("timestep=\"0.01\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("particles_000002.vtu"), std::string::npos) << pvd;
  const auto arrays = gf::io::readVtkArrays(readAll(dir.file("o/particles_000002.vtu")));
  ASSERT_TRUE(arrays.count("radius"));
  EXPECT_EQ(arrays.at("radius").real.size(), 64u);
  const auto csv = gf::io::readCsv(dir.file("o/particle_count.csv"));
  EXPECT_EQ(csv.header.at(0), "time [s]");
  EXPECT_EQ(csv.header.at(1), "particles [-]");
  EXPECT_EQ(csv.rows.size(), 6u);  // t = 0, 0.002, ..., 0.01
  EXPECT_DOUBLE_EQ(csv.rows.back().at(1), 64.0);
}

TEST(Run, ParticleLeavingDomainStopsWithStepIdAndPlaceAndKeepsCheckpoint) {
  TempDir dir;
  std::string text = kCase;
  text.replace(text.find("walls: [{type: plane, point: [0, 0, 0], normal: [0, 0, 1]}]"),
               std::string("walls: [{type: plane, point: [0, 0, 0], normal: [0, 0, 1]}]").size(), "walls: []");
  text += "checkpoint: {interval_steps: 100}\n";
  const std::string file = dir.write("case.yaml", text);
  const auto r = grainflow("run " + file + " --quiet --output " + dir.file("o"));
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("run diverged at step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle left the domain"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle id"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at position ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("last good checkpoint kept"), std::string::npos) << r.output;
  // The kept checkpoint is valid: restarting from it reaches the same divergence, not a checkpoint error.
  const auto again = grainflow("run " + file + " --quiet --output " + dir.file("o") + " --restart " + dir.file("o/checkpoint.bin"));
  EXPECT_EQ(again.exitCode, 3) << again.output;
}

TEST(Run, InterruptWritesCheckpointThatContinues) {
  TempDir dir;
  std::string text = kCase;
  text.replace(text.find("end: 0.04"), 9, "end: 100.0");
  text.replace(text.find("velocity: [0.01, -0.02, -0.1]"), 29, "velocity: [0.0, 0.0, -0.1]");
  const std::string file = dir.write("case.yaml", text);
  const std::string cmd = "bash -c '" + std::string(GRAINFLOW_BINARY) + " run " + file + " --quiet --output " +
                          dir.file("o") + " & pid=$!; sleep 1.5; kill -INT $pid; wait $pid; echo exit=$?'";
  const auto r = gf::testing::runShell(cmd);
  EXPECT_NE(r.output.find("exit=130"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("checkpoint written"), std::string::npos) << r.output;
  ASSERT_TRUE(std::filesystem::exists(dir.file("o/checkpoint.bin")));
  const auto resumed = grainflow("run " + file + " --quiet --end-time 0.0 --output " + dir.file("o") + " --restart " +
                                 dir.file("o/checkpoint.bin"));
  EXPECT_EQ(resumed.exitCode, 0) << resumed.output;
}

TEST(Run, EveryExampleCaseChecks) {
  for (const auto& entry : std::filesystem::directory_iterator(gf::testing::sourcePath("cases"))) {
    if (entry.path().extension() != ".yaml") continue;
    const auto r = grainflow("check " + entry.path().string());
    EXPECT_EQ(r.exitCode, 0) << entry.path() << "\n" << r.output;
  }
}

TEST(Run, DemoCaseFallingSpheresRunsAndSettles) {
  TempDir dir;
  const auto r = grainflow("run " + gf::testing::sourcePath("cases/falling_spheres.yaml") +
                           " --quiet --end-time 0.12 --output " + dir.file("o"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto arrays = gf::io::readVtkArrays(readAll(dir.file("o/particles_000012.vtu")));
  const auto& points = arrays.at("Points").real;
  ASSERT_EQ(points.size(), 3u * 500u);
  double lowest = 1.0;
  for (std::size_t i = 2; i < points.size(); i += 3) lowest = std::min(lowest, points[i]);
  // The bottom layer rests on the floor: centre about one radius (2 mm) above it, overlap small.
  EXPECT_NEAR(lowest, 0.002, 0.0002);
}

TEST(Docs, CaseFileReferenceMatchesSchema) {
  const auto r = grainflow("docs");
  ASSERT_EQ(r.exitCode, 0);
  EXPECT_EQ(r.output, readAll(gf::testing::sourcePath("docs/case-file.md")))
      << "docs/case-file.md is out of date: regenerate it with `build/grainflow docs > docs/case-file.md`";
}

TEST(Run, FluidCflBlowUpStopsWithCellAndKeepsCheckpoint) {
  // 20 m/s through 1 cm cells with a 1 ms fluid step: CFL = 2 > cfl_limit = 1.
  const std::string text = R"(case: {name: cfl}
domain: {min: [0, 0, 0], max: [0.04, 0.04, 0.08]}
time: {end: 0.05, dem_step: 1.0e-5, coupling_interval: 100}
materials: [{name: glass, density: 2500.0, youngs_modulus: 5.0e6}]
walls: [{type: plane, point: [0, 0, 0], normal: [0, 0, 1]}]
insertion: [{type: lattice, material: glass, origin: [0.02, 0.02, 0.002], spacing: 0.01, diameter: 0.004}]
fluid:
  cells: [4, 4, 8]
  boundaries:
    z_min: {type: inlet, velocity: [0, 0, 20.0]}
    z_max: {type: pressure_outlet}
checkpoint: {interval_steps: 100}
)";
  TempDir dir;
  const std::string file = dir.write("case.yaml", text);
  const auto r = grainflow("run " + file + " --quiet --threads 1 --output " + dir.file("o"));
  EXPECT_EQ(r.exitCode, 3) << r.output;
  EXPECT_NE(r.output.find("run diverged at step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fluid CFL number"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fluid cell ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("at position ("), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("o/checkpoint.bin")) ||
              r.output.find("no checkpoint had been written") != std::string::npos)
      << r.output;
}
