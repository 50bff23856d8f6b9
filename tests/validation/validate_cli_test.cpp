// `grainflow validate` and `grainflow plot` as a user runs them: the quick suite of the repository
// passes, failures give a non-zero exit, full mode writes the report, every item is in the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "../app/run_helper.hpp"
#include "app/plot.hpp"
#include "app/validate.hpp"
#include "app/validation_spec.hpp"

using gf::testing::grainflow;
using gf::testing::readAll;
using gf::testing::runShell;
using gf::testing::sourcePath;
using gf::testing::TempDir;

namespace fs = std::filesystem;

namespace {
// A one-sphere free-fall item small enough to run in a blink; {tolerance} is filled in per test.
const std::string kCase = R"(domain: {min: [0, 0, 0], max: [0.1, 0.1, 1.0]}
time: {end: 0.1, dem_step: 2.0e-5}
materials: [{name: glass, density: 2500.0}]
insertion: [{type: lattice, origin: [0.05, 0.05, 0.5], spacing: 0.01, diameter: 0.004}]
monitors:
  - {type: particle_probe, name: probe, id: 0, interval: 0.01}
)";
std::string itemYaml(const std::string& tolerance) {
  return R"(title: Tiny free fall
quick: {time.end: 0.05}
quantities:
  - name: drop
    monitor: probe
    column: z
    operation: final
    scale: -1.0
    offset: 0.5
    reference: {value: 0.0490500, source: "g t^2/2 at t = 0.1 s"}
    tolerance: )" + tolerance + "\n";
}

void writeItem(const TempDir& dir, const std::string& name, const std::string& yaml) {
  fs::create_directories(dir.path() / "validation" / name);
  dir.write("validation/" + name + "/validation.yaml", yaml);
  dir.write("validation/" + name + "/case.yaml", kCase);
}
}  // namespace

TEST(ValidateCli, QuickSuiteOfTheRepositoryPasses) {
  TempDir dir;
  const auto r = grainflow("validate --threads 1 --quick --no-plots --dir " + sourcePath("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  for (const char* head : {"case", "quantity", "reference", "grainflow", "error", "tolerance", "result"})
    EXPECT_NE(r.output.find(head), std::string::npos) << head;
  EXPECT_EQ(r.output.find("FAIL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ETA"), std::string::npos);
  for (const std::string& item : gf::app::validation::listItems(sourcePath("validation")))
    EXPECT_NE(r.output.find(item + " "), std::string::npos) << item << " not in the table";
  const std::string csv = readAll(dir.file("out/results.csv"));
  EXPECT_EQ(csv.rfind("item,run,quantity,operation,reference,grainflow,error,tolerance,tolerance_type,pass,note\n", 0), 0u);
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 5);
}

TEST(ValidateCli, EveryItemIsListedInTheReport) {
  const std::string report = readAll(sourcePath("docs/validation.md"));
  ASSERT_FALSE(report.empty()) << "docs/validation.md missing: run `grainflow validate` (full mode) in the repository";
  for (const std::string& item : gf::app::validation::listItems(sourcePath("validation")))
    EXPECT_NE(report.find("## `" + item + "`"), std::string::npos)
        << "validation item '" << item << "' is not in docs/validation.md: rerun `grainflow validate` (full mode)";
}

TEST(ValidateCli, EveryItemLoads) {
  for (const std::string& item : gf::app::validation::listItems(sourcePath("validation")))
    EXPECT_NO_THROW(gf::app::validation::loadItem(sourcePath("validation/" + item))) << item;
}

TEST(ValidateCli, FailingComparisonGivesNonZeroExitAndFailRow) {
  TempDir dir;
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-6}"));  // the quick run stops at 0.05 s: far off
  const auto r = grainflow("validate --threads 1 --quick --no-plots --dir " + dir.file("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, gf::app::kExitValidationFailed) << r.output;
  EXPECT_NE(r.output.find("FAIL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0 of 1 comparison(s) passed"), std::string::npos) << r.output;
}

TEST(ValidateCli, DivergedRunIsAFailedComparisonAndTheOthersStillRun) {
  TempDir dir;
  writeItem(dir, "good", itemYaml("{relative: 1.0e-3}"));
  writeItem(dir, "lost", itemYaml("{relative: 1.0e-3}"));
  // The sphere falls out of a domain that ends 1 cm below it: the run diverges ("left the domain").
  std::string lostCase = kCase;
  lostCase.replace(lostCase.find("min: [0, 0, 0]"), 14, "min: [0, 0, 0.49]");
  dir.write("validation/lost/case.yaml", lostCase);
  const auto r = grainflow("validate --threads 1 --no-plots --no-docs --dir " + dir.file("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, gf::app::kExitValidationFailed) << r.output;
  EXPECT_NE(r.output.find("DIVERGED"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("left the domain"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 of 2 comparison(s) passed"), std::string::npos) << r.output;
}

TEST(ValidateCli, FullModeWritesTheReportWithProvenance) {
  TempDir dir;
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-3}"));
  writeItem(dir, "other", itemYaml("{absolute: 1.0e-6}"));
  const auto r = grainflow("validate --threads 1 --no-plots --dir " + dir.file("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  const std::string report = readAll(dir.file("docs/validation.md"));
  for (const char* text : {"## `tiny`", "## `other`", "Commit:", "Machine: `Linux", "CPU:", "Date:", "| [`tiny`](#tiny)", "pass"})
    EXPECT_NE(report.find(text), std::string::npos) << text << "\n" << report;
  // Named items or --quick never rewrite the report.
  fs::remove(dir.file("docs/validation.md"));
  EXPECT_EQ(grainflow("validate --threads 1 --no-plots tiny --dir " + dir.file("validation") + " --output " + dir.file("out")).exitCode, 0);
  // (the quick run stops at 0.05 s, so its comparison fails by design: exit 6)
  EXPECT_EQ(grainflow("validate --threads 1 --quick --no-plots --dir " + dir.file("validation") + " --output " + dir.file("out")).exitCode,
            gf::app::kExitValidationFailed);
  EXPECT_FALSE(fs::exists(dir.file("docs/validation.md")));
}

TEST(ValidateCli, BadItemOrNameIsAnInputError) {
  TempDir dir;
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-3}") + "colour: red\n");
  auto r = grainflow("validate --threads 1 --quick --dir " + dir.file("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("validation.yaml:"), std::string::npos) << r.output;
  r = grainflow("validate --threads 1 nosuchitem --dir " + dir.file("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("available: tiny"), std::string::npos) << r.output;
}

TEST(ValidateCli, WithoutMatplotlibNumbersStillComeAndTheHintIsPrinted) {
  TempDir dir;
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-3}"));
  const auto r = runShell("GRAINFLOW_PYTHON=/nonexistent/python3 " + std::string(GRAINFLOW_BINARY) + " validate --threads 1 --dir " +
                          dir.file("validation") + " --output " + dir.file("out") + " --no-docs");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("PASS"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("apt-get install python3-matplotlib"), std::string::npos) << r.output;
  const auto p = runShell("GRAINFLOW_PYTHON=/nonexistent/python3 " + std::string(GRAINFLOW_BINARY) + " plot " +
                          dir.file("out/tiny/run"));
  EXPECT_NE(p.exitCode, 0);
  EXPECT_NE(p.output.find("apt-get install python3-matplotlib"), std::string::npos) << p.output;
}

TEST(PlotCli, WritesOnePngPerMonitorCsvAndValidationFigures) {
  const gf::app::PlotTool tool = gf::app::findPlotTool(sourcePath(""));
  if (!tool.available()) GTEST_SKIP() << "plotting unavailable: " << tool.problem << "; " << gf::app::kPlotInstallHint;
  TempDir dir;
  const std::string file = dir.write("case.yaml", kCase + "  - {type: particle_statistics, interval: 0.02}\n");
  ASSERT_EQ(grainflow("run " + file + " --quiet --threads 1 --output " + dir.file("run")).exitCode, 0);
  const auto r = grainflow("plot " + dir.file("run"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* png : {"run/probe.png", "run/particle_statistics.png"}) {
    const std::string bytes = readAll(dir.file(png));
    ASSERT_GT(bytes.size(), 1000u) << png;
    EXPECT_EQ(bytes.substr(1, 3), "PNG") << png;
  }
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-3}"));
  const auto v = grainflow("validate --threads 1 --dir " + dir.file("validation") + " --output " + dir.file("out") + " --no-docs");
  ASSERT_EQ(v.exitCode, 0) << v.output;
  EXPECT_EQ(readAll(dir.file("out/tiny/tiny_drop.png")).substr(1, 3), "PNG") << v.output;
}
