// `grainflow validate` and `grainflow plot` as a user runs them: the quick suite of the repository
// passes, failures give a non-zero exit, full mode writes the report, every item is in the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "../app/run_helper.hpp"
#include "app/plot.hpp"
#include "app/validate.hpp"
#include "app/validation_spec.hpp"
#include "io/csv_series.hpp"

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

// The repository's quick suite in two tests that ctest can run side by side: the resolved CFD-DEM
// items (minutes each) and all the others.
static void runQuickSuite(bool resolvedItems) {
  std::vector<std::string> names;
  for (const std::string& item : gf::app::validation::listItems(sourcePath("validation")))
    if ((item.rfind("resolved_", 0) == 0) == resolvedItems) names.push_back(item);
  if (names.empty()) GTEST_SKIP() << "no such items";
  std::string list;
  for (const std::string& name : names) list += " " + name;
  TempDir dir;
  const auto r = grainflow("validate --threads 1 --quick --no-plots --dir " + sourcePath("validation") + " --output " + dir.file("out") + list);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  for (const char* head : {"case", "quantity", "reference", "grainflow", "error", "tolerance", "result"})
    EXPECT_NE(r.output.find(head), std::string::npos) << head;
  EXPECT_EQ(r.output.find("FAIL"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ETA"), std::string::npos);
  for (const std::string& item : names) EXPECT_NE(r.output.find(item + " "), std::string::npos) << item << " not in the table";
  const std::string csv = readAll(dir.file("out/results.csv"));
  EXPECT_EQ(csv.rfind("item,run,quantity,operation,reference,grainflow,error,tolerance,tolerance_type,pass,note\n", 0), 0u);
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), resolvedItems ? 1 : 5);
}

TEST(ValidateCli, QuickSuiteOfTheRepositoryPasses) { runQuickSuite(false); }

TEST(ValidateCli, QuickSuiteOfTheResolvedItemsPasses) { runQuickSuite(true); }

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

TEST(ValidateCli, ReportQuickItemRunsWithItsQuickSettingsInTheReportOnly) {
  // report_quick: the full report runs the item with its --quick settings (the free fall stops at
  // 0.05 s, so the comparison made for 0.1 s fails) and says so; named, the item runs in full.
  TempDir dir;
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-3}") + "report_quick: true\n");
  writeItem(dir, "other", itemYaml("{relative: 1.0e-3}"));
  auto r = grainflow("validate --threads 1 --no-plots --dir " + dir.file("validation") + " --output " + dir.file("out"));
  EXPECT_EQ(r.exitCode, gf::app::kExitValidationFailed) << r.output;
  EXPECT_NE(r.output.find("1 of 2 comparison(s) passed"), std::string::npos) << r.output;
  const std::string report = readAll(dir.file("docs/validation.md"));
  for (const char* text : {"Run in this report with its `--quick` settings", "`grainflow validate tiny` runs it in full",
                           "Tiny free fall (quick settings)"})
    EXPECT_NE(report.find(text), std::string::npos) << text << "\n" << report;
  EXPECT_NE(readAll(dir.file("out/tiny/run/case.yaml")).find("--quick"), std::string::npos);
  r = grainflow("validate --threads 1 --no-plots tiny --dir " + dir.file("validation") + " --output " + dir.file("out2"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  // report_quick with skip_quick is refused
  writeItem(dir, "both", itemYaml("{relative: 1.0e-3}") + "report_quick: true\nskip_quick: true\n");
  r = grainflow("validate --threads 1 --quick both --dir " + dir.file("validation") + " --output " + dir.file("out3"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("report_quick"), std::string::npos) << r.output;
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

namespace {
// A uniform stream in a periodic box stays uniform: its profiles are known exactly.
const std::string kProfileCase = R"(domain: {min: [0, 0, 0], max: [0.5, 1.0, 0.1], periodic: [1, 1, 1]}
gravity: [0, 0, 0]
materials: [{name: unused, density: 1000.0}]
time: {end: 0.2, dem_step: 0.05}
fluid: {density: 1.0, viscosity: 0.01, cells: [4, 8, 1], initial: {velocity: [0.3, 0.0, 0.0]}}
monitors:
  - {type: fluid_line_profile, name: across, line_axis: y, line_point: [0.25, 0.5, 0.05], interval: 0.1}
  - {type: fluid_line_profile, name: along, line_axis: x, line_point: [0.25, 0.5, 0.05], interval: 0.1}
)";
const std::string kProfileItem = R"yaml(title: Uniform stream profiles
quantities:
  - name: u(y)
    monitor: across
    column: velocity_x
    x_column: y
    operation: profile
    reference: {points: [[0.0, 0.3], [0.5, 0.3], [0.8125, 0.3], [1.0, 0.3]], source: "uniform initial stream"}
    tolerance: {absolute: 1.0e-12}
    plot: {figure: both profiles, swap_axes: true}
  - name: v(x)
    monitor: along
    column: velocity_y
    x_column: x
    operation: profile
    reference: {points: [[0.1875, 0.0]], source: "uniform initial stream"}
    tolerance: {absolute: 1.0e-12}
    plot: {figure: both profiles}
)yaml";
}  // namespace

TEST(ValidateCli, ProfileComparesEachReferencePointInsideTheLineOnOneFigure) {
  TempDir dir;
  fs::create_directories(dir.path() / "validation" / "stream");
  dir.write("validation/stream/validation.yaml", kProfileItem);
  dir.write("validation/stream/case.yaml", kProfileCase);
  const auto r = grainflow("validate --threads 1 --no-docs --dir " + dir.file("validation") + " --output " + dir.file("out"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // Wall values y = 0 and y = 1 lie beyond the cell centres 1/16 ... 15/16: drawn, not compared.
  EXPECT_NE(r.output.find("u(y): y = 0.5 "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("u(y): y = 0.8125 "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("v(x): x = 0.1875 "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 of 3 comparison(s) passed"), std::string::npos) << r.output;
  // The monitor wrote one row per cell at each of its three samples (t = 0, 0.1, 0.2).
  const auto table = gf::io::readCsv(dir.file("out/stream/run/across.csv"));
  EXPECT_EQ(table.header.front(), "time [s]");
  EXPECT_EQ(table.header[1], "y [m]");
  ASSERT_EQ(table.rows.size(), 24u);
  EXPECT_DOUBLE_EQ(table.rows[23][0], 0.2);
  EXPECT_DOUBLE_EQ(table.rows[16][0], 0.2);
  EXPECT_DOUBLE_EQ(table.rows[15][0], 0.1);
  // Both quantities share one figure: one spec with two panels, no PNG per point.
  const std::string spec = readAll(dir.file("out/stream/stream_both_profiles.plot.json"));
  EXPECT_NE(spec.find("\"panels\""), std::string::npos);
  EXPECT_NE(spec.find("\"swap_axes\": true"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir.file("out/stream/stream_u_y.plot.json")));
  const gf::app::PlotTool tool = gf::app::findPlotTool(sourcePath(""));
  if (tool.available()) {
    EXPECT_EQ(readAll(dir.file("out/stream/stream_both_profiles.png")).substr(1, 3), "PNG") << r.output;
    std::size_t pngs = 0;
    for (const auto& entry : fs::directory_iterator(dir.path() / "out" / "stream")) pngs += entry.path().extension() == ".png";
    EXPECT_EQ(pngs, 1u);
  }
}

TEST(ValidateCli, ReportNamesTheCommitAndOnlyChangesThatAreNotItsOwnOutput) {
  if (runShell("git --version").exitCode != 0) GTEST_SKIP() << "git not installed";
  TempDir dir;
  writeItem(dir, "tiny", itemYaml("{relative: 1.0e-3}"));
  dir.write(".gitignore", "/out/\n");  // as output/ in the repository
  fs::create_directories(dir.path() / "docs" / "img");
  // A previous report showed old.png; the README shows kept.png.
  dir.write("docs/validation.md", "![old](img/old.png)\n![kept](img/kept.png)\n");
  dir.write("docs/img/old.png", "x");
  dir.write("docs/img/kept.png", "x");
  dir.write("README.md", "# Test\n<!-- validation-summary:begin -->\n<!-- validation-summary:end -->\n![kept](docs/img/kept.png)\n");
  const std::string git = "git -C " + dir.path().string() + " -c user.name=test -c user.email=test@example.com ";
  ASSERT_EQ(runShell(git + "init -q && " + git + "add -A && " + git + "commit -q -m items").exitCode, 0);
  const std::string head = runShell(git + "rev-parse --short=12 HEAD").output.substr(0, 12);
  const std::string validate = "validate --threads 1 --no-plots --dir " + dir.file("validation") + " --output " + dir.file("out");

  auto r = grainflow(validate);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::string report = readAll(dir.file("docs/validation.md"));
  EXPECT_NE(report.find("- Commit: `" + head + "`\n"), std::string::npos) << report;
  EXPECT_EQ(r.output.find("uncommitted"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("docs/img/old.png")));  // no longer in the report
  EXPECT_TRUE(fs::exists(dir.file("docs/img/kept.png")));  // the README shows it

  // The run rewrote docs/validation.md and README.md: a rerun does not count its own output.
  ASSERT_NE(runShell(git + "status --porcelain").output, "");
  r = grainflow(validate);
  EXPECT_NE(readAll(dir.file("docs/validation.md")).find("- Commit: `" + head + "`\n"), std::string::npos);

  // A changed case or a new untracked file is a change the report names, and the start says so.
  dir.write("validation/tiny/case.yaml", kCase + "# changed\n");
  dir.write("validation/tiny/notes.txt", "new");
  r = grainflow(validate);
  EXPECT_NE(r.output.find("note: 2 uncommitted change(s)"), std::string::npos) << r.output;
  report = readAll(dir.file("docs/validation.md"));
  EXPECT_NE(report.find("`" + head + "` (with uncommitted changes: `validation/tiny/case.yaml`, `validation/tiny/notes.txt`)"),
            std::string::npos)
      << report;
}
