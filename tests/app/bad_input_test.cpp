// Bad input must give a precise message (file, line, key, found, expected), a non-zero exit code,
// and no output. Exit codes: 1 invalid case, 2 usage, 3 diverged, 4 checkpoint, 5 I/O.
#include <gtest/gtest.h>

#include <filesystem>

#include "run_helper.hpp"

using gf::testing::grainflow;
using gf::testing::TempDir;

namespace {

// A small valid case; each test breaks one thing in it.
const std::string kValidCase = R"(case:
  name: small
domain:
  min: [0.0, 0.0, 0.0]
  max: [0.02, 0.02, 0.05]
time:
  end: 0.01
  dem_step: 2.0e-5
materials:
  - name: glass
    density: 2500.0
    youngs_modulus: 5.0e6
walls:
  - type: plane
    point: [0.0, 0.0, 0.0]
    normal: [0.0, 0.0, 1.0]
insertion:
  - type: lattice
    material: glass
    origin: [0.005, 0.005, 0.005]
    spacing: 0.005
    nx: 2
    ny: 2
    nz: 2
    diameter: 0.004
output:
  interval: 0.005
monitors:
  - type: particle_count
)";

std::string replaced(const std::string& from, const std::string& to) {
  std::string text = kValidCase;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in the base case";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

struct Expectation {
  int exitCode;
  std::vector<std::string> fragments;
};

void expectCheckFails(const std::string& caseText, const Expectation& e) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", caseText);
  const auto check = grainflow("check " + file);
  EXPECT_EQ(check.exitCode, e.exitCode) << check.output;
  for (const auto& f : e.fragments) EXPECT_NE(check.output.find(f), std::string::npos) << "missing '" << f << "' in:\n" << check.output;
  // `run` refuses the same input before writing anything.
  const auto run = grainflow("run " + file + " --output " + dir.file("out"));
  EXPECT_EQ(run.exitCode, e.exitCode) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << "output written for a bad case";
}

}  // namespace

TEST(BadInput, ValidBaseCasePasses) {
  TempDir dir;
  const auto r = grainflow("check " + dir.write("case.yaml", kValidCase));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("insertion[0].diameter: 0.004  # [m]"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("gravity: [0, 0, -9.81]  # [m/s^2] (default)"), std::string::npos) << r.output;
}

TEST(BadInput, MissingFile) {
  const auto r = grainflow("check /nonexistent/case.yaml");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("/nonexistent/case.yaml: error"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no such file"), std::string::npos) << r.output;
}

TEST(BadInput, EmptyFile) { expectCheckFails("", {1, {"case.yaml", "an empty file", "a YAML map"}}); }

TEST(BadInput, NotYaml) {
  expectCheckFails("domain: [1, 2\ntime: {end: }}\n", {1, {"case.yaml:", "not valid YAML"}});
}

TEST(BadInput, TopLevelIsAList) { expectCheckFails("- a\n- b\n", {1, {"case.yaml:1:1", "a list", "a YAML map"}}); }

TEST(BadInput, WrongType) {
  expectCheckFails(replaced("density: 2500.0", "density: heavy"),
                   {1, {"case.yaml:11:14", "materials[0].density", "found 'heavy'", "a number [kg/m^3]"}});
}

TEST(BadInput, NegativeDiameter) {
  expectCheckFails(replaced("diameter: 0.004", "diameter: -0.004"),
                   {1, {"case.yaml:25:15", "insertion[0].diameter", "found -0.004", "a value > 0 [m]"}});
}

TEST(BadInput, ZeroDensity) {
  expectCheckFails(replaced("density: 2500.0", "density: 0"), {1, {"materials[0].density", "found 0", "> 0"}});
}

TEST(BadInput, UnknownKeyWithSuggestion) {
  expectCheckFails(replaced("youngs_modulus: 5.0e6", "youngs_modulos: 5.0e6"),
                   {1, {"case.yaml:12:5", "materials[0].youngs_modulos", "did you mean 'youngs_modulus'"}});
}

TEST(BadInput, UnknownTopLevelSection) {
  expectCheckFails(kValidCase + "partciles:\n  n: 3\n", {1, {"key 'partciles'", "unknown key"}});
}

TEST(BadInput, UnknownModelListsRegistered) {
  expectCheckFails(replaced("type: particle_count", "type: particle_cnt"),
                   {1, {"monitors[0].type", "'particle_cnt'", "did you mean 'particle_count'", "one of:"}});
}

TEST(BadInput, ParticleOutsideDomain) {
  expectCheckFails(replaced("origin: [0.005, 0.005, 0.005]", "origin: [0.005, 0.005, 0.049]"),
                   {1, {"insertion[0].origin", "outside the domain"}});
}

TEST(BadInput, DomainMaxBelowMin) {
  expectCheckFails(replaced("max: [0.02, 0.02, 0.05]", "max: [0.02, -0.02, 0.05]"),
                   {1, {"domain.max", "max[1] = -0.02 <= min[1] = 0"}});
}

TEST(BadInput, NegativeEndTime) {
  expectCheckFails(replaced("end: 0.01", "end: -1"), {1, {"case.yaml:7:8", "time.end", "found -1", ">= 0 [s]"}});
}

TEST(BadInput, TimeStepAboveStabilityLimit) {
  expectCheckFails(replaced("dem_step: 2.0e-5", "dem_step: 2.0e-4"),
                   {1, {"time.dem_step", "Rayleigh time", "at most 50 %"}});
}

// A rate-based insertion makes its particles later in the run: the step is checked against its
// smallest sphere (0.4 mm here, 10x smaller than the lattice's) before the run starts.
TEST(BadInput, TimeStepAboveStabilityLimitOfARateInsertionsParticles) {
  const std::string rate = R"(  - {type: rate, material: glass, corner: [0.002, 0.002, 0.04], edge_a: [0.01, 0, 0], edge_b: [0, 0.01, 0],
     mass_flow_rate: 0.001, start: 0.005, end: 0.01, size: {distribution: discrete, diameters: [0.0004, 0.001],
     mass_fractions: [0.5, 0.5]}}
output:)";
  expectCheckFails(replaced("output:", rate), {1, {"time.dem_step", "Rayleigh time", "at most 50 %"}});
  // and without the small spheres the same step passes
  TempDir dir;
  const auto ok = grainflow("check " + dir.write("case.yaml", kValidCase));
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
}

TEST(BadInput, VectorWithTwoComponents) {
  expectCheckFails(kValidCase + "gravity: [0.0, -9.81]\n", {1, {"gravity", "a list of 2 item(s)", "3 numbers"}});
}

TEST(BadInput, MissingRequiredSection) {
  std::string text = kValidCase;
  text.erase(text.find("time:"), std::string("time:\n  end: 0.01\n  dem_step: 2.0e-5\n").size());
  expectCheckFails(text, {1, {"key 'time'", "this section is required"}});
}

TEST(BadInput, UnknownMaterialName) {
  expectCheckFails(replaced("material: glass", "material: steel"),
                   {1, {"insertion[0].material", "'steel'", "one of the materials: glass"}});
}

TEST(BadInput, OutputDirectoryNotWritable) {
  TempDir dir;
  dir.write("a_file", "x");
  const std::string file = dir.write("case.yaml", kValidCase);
  const auto r = grainflow("run " + file + " --output " + dir.file("a_file/out"));
  EXPECT_EQ(r.exitCode, 5) << r.output;
  EXPECT_NE(r.output.find("cannot be created"), std::string::npos) << r.output;
}

TEST(BadInput, RefusesToOverwriteAnotherRun) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kValidCase);
  const std::string out = dir.file("out");
  ASSERT_EQ(grainflow("run " + file + " --quiet --output " + out).exitCode, 0);
  const auto again = grainflow("run " + file + " --quiet --output " + out);
  EXPECT_EQ(again.exitCode, 5) << again.output;
  EXPECT_NE(again.output.find("already holds a run"), std::string::npos) << again.output;
  EXPECT_EQ(grainflow("run " + file + " --quiet --overwrite --output " + out).exitCode, 0);
}

/// Runs the valid case, damages its checkpoint with `damage` and restarts from the damaged copy.
template <class Damage>
gf::testing::CommandResult restartFromDamagedCheckpoint(Damage damage) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kValidCase);
  EXPECT_EQ(grainflow("run " + file + " --quiet --output " + dir.file("out")).exitCode, 0);
  std::string bytes = gf::testing::readAll(dir.file("out/checkpoint.bin"));
  EXPECT_GT(bytes.size(), 200u);
  damage(bytes);
  dir.write("damaged.bin", bytes);
  return grainflow("run " + file + " --quiet --output " + dir.file("out") + " --restart " + dir.file("damaged.bin"));
}

TEST(BadInput, CorruptCheckpoint) {
  const auto r = restartFromDamagedCheckpoint([](std::string& bytes) { bytes[bytes.size() / 2] ^= 0x5A; });
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("checksum mismatch"), std::string::npos) << r.output;
}

TEST(BadInput, TruncatedCheckpoint) {
  const auto r = restartFromDamagedCheckpoint([](std::string& bytes) { bytes.resize(bytes.size() - 100); });
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
}

TEST(BadInput, CheckpointFromAnotherCase) {
  TempDir dir;
  const std::string fileA = dir.write("a.yaml", kValidCase);
  const std::string fileB = dir.write("b.yaml", replaced("diameter: 0.004", "diameter: 0.003"));
  ASSERT_EQ(grainflow("run " + fileA + " --quiet --output " + dir.file("outA")).exitCode, 0);
  const auto r = grainflow("run " + fileB + " --quiet --output " + dir.file("outB") + " --restart " + dir.file("outA/checkpoint.bin"));
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("written for another case"), std::string::npos) << r.output;
}

TEST(BadInput, NotACheckpoint) {
  TempDir dir;
  const std::string file = dir.write("case.yaml", kValidCase);
  const auto r = grainflow("run " + file + " --quiet --output " + dir.file("out") + " --restart " + file);
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find("not a grainflow checkpoint"), std::string::npos) << r.output;
}

TEST(BadInput, CommandLineUsage) {
  EXPECT_EQ(grainflow("run").exitCode, 2);
  EXPECT_EQ(grainflow("frobnicate").exitCode, 2);
  EXPECT_EQ(grainflow("run x.yaml --threads -3").exitCode, 2);
}

TEST(BadInput, OverlappingWallsBoxAndFloor) {
  // A box already has a floor at z = 0; a second plane there would push particles twice.
  expectCheckFails(replaced("    normal: [0.0, 0.0, 1.0]\n",
                            "    normal: [0.0, 0.0, 1.0]\n  - {type: box, min: [0.0, 0.0, 0.0], max: [0.02, 0.02, 0.05]}\n"),
                   {1, {"walls[1].type", "already has one", "walls that do not overlap"}});
}

TEST(BadInput, FacingWallsWithNoRoomBetween) {
  expectCheckFails(replaced("    normal: [0.0, 0.0, 1.0]\n", "    normal: [0.0, 0.0, 1.0]\n  - type: plane\n    point: [0.0, 0.0, -0.01]\n    normal: [0.0, 0.0, -1.0]\n"),
                   {1, {"walls[1].type", "faces wall", "they overlap"}});
}
