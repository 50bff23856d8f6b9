// validation.yaml loading (strict keys, file:line errors) and case overrides by key path.
#include <gtest/gtest.h>

#include "../app/run_helper.hpp"
#include "app/validation_spec.hpp"
#include "core/error.hpp"
#include "core/params.hpp"

using namespace gf::app::validation;
using gf::testing::TempDir;

namespace {
const std::string kItem = R"(title: Test item
case: case.yaml
quick: {time.end: 0.1, "materials[0].restitution": 0.7}
sweep:
  key: materials[0].youngs_modulus
  values: [1.0e6, 2.0e6, 4.0e6]
  quick_values: [1.0e6, 4.0e6]
  with: {time.dem_step: [1.0e-5, 2.0e-5, 4.0e-5]}
quantities:
  - name: top
    monitor: stats
    column: z_max
    operation: final
    reference: {file: ref.csv, x: E, y: top, source: "made up for the test"}
    tolerance: {relative: 0.01}
  - name: order
    monitor: stats
    column: z_max
    across_runs: loglog_slope
    reference: {value: -0.5, source: "made up"}
    tolerance: {absolute: 0.1}
)";
const std::string kRef = "# comment line\nE [Pa],top [m]\n1e6,0.1\n4e6,0.2\n";
const std::string kCase = "time: {end: 1.0, dem_step: 1.0e-5}\nmaterials:\n  - {name: a, density: 1.0}\n";

std::string itemDir(const TempDir& dir, const std::string& item, const std::string& ref = kRef) {
  std::filesystem::create_directories(dir.path() / "it");
  dir.write("it/validation.yaml", item);
  dir.write("it/case.yaml", kCase);
  dir.write("it/ref.csv", ref);
  return dir.file("it");
}

std::string loadError(const std::string& item, const std::string& ref = kRef) {
  TempDir dir;
  try {
    loadItem(itemDir(dir, item, ref));
  } catch (const gf::CaseError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}
}  // namespace

TEST(ValidationSpec, LoadsSweepQuickValuesWithKeysAndReference) {
  TempDir dir;
  const Item item = loadItem(itemDir(dir, kItem));
  EXPECT_EQ(item.name, "it");
  ASSERT_EQ(item.runs.size(), 3u);
  ASSERT_EQ(item.quickRuns.size(), 2u);
  EXPECT_DOUBLE_EQ(item.quickRuns[1].x, 4.0e6);
  ASSERT_EQ(item.quickRuns[1].overrides.size(), 2u);  // the swept key and its 'with' partner
  EXPECT_EQ(item.quickRuns[1].overrides[1].path, "time.dem_step");
  EXPECT_EQ(item.quickRuns[1].overrides[1].yaml, "4.0e-5");
  ASSERT_EQ(item.quickOverrides.size(), 2u);
  ASSERT_EQ(item.quantities.size(), 2u);
  EXPECT_EQ(item.quantities[0].reference.data.x.size(), 2u);  // comment skipped
  EXPECT_TRUE(item.quantities[0].tolerance.relative);
  EXPECT_EQ(item.quantities[1].across, AcrossRuns::LogLogSlope);
}

TEST(ValidationSpec, RejectsUnknownKeysWithLineAndSuggestion) {
  const std::string e = loadError(replaced(kItem, "    operation: final", "    operatoin: final"));
  EXPECT_NE(e.find("validation.yaml:13:5"), std::string::npos) << e;
  EXPECT_NE(e.find("'operation'"), std::string::npos) << e;
}

TEST(ValidationSpec, RejectsBadValues) {
  EXPECT_NE(loadError(replaced(kItem, "operation: final", "operation: median")).find("one of: final"), std::string::npos);
  EXPECT_NE(loadError(replaced(kItem, "{relative: 0.01}", "{relative: 0.01, absolute: 1}")).find("exactly one"), std::string::npos);
  EXPECT_NE(loadError(replaced(kItem, "y: top,", "y: bottom,")).find("no column 'bottom'"), std::string::npos);
  EXPECT_NE(loadError(replaced(kItem, "file: ref.csv", "file: nothere.csv")).find("missing"), std::string::npos);
  EXPECT_NE(loadError(replaced(kItem, "[1.0e-5, 2.0e-5, 4.0e-5]", "[1.0e-5]")).find("one per swept value"), std::string::npos);
  EXPECT_NE(loadError(replaced(kItem, "quick_values: [1.0e6, 4.0e6]", "quick_values: [3.0e6]")).find("out of 'values'"),
            std::string::npos);
  EXPECT_NE(loadError(kItem, "E [Pa],top [m]\n4e6,0.2\n1e6,0.1\n").find("not sorted"), std::string::npos);
  EXPECT_NE(loadError("title: x\nquantities: []\n").find("quantities"), std::string::npos);
  EXPECT_NE(loadError(replaced(kItem, "    reference: {value: -0.5, source: \"made up\"}", "    reference: {value: -0.5}")).find("source"),
            std::string::npos);
}

TEST(ValidationSpec, AcrossRunsKindsAndLowerBound) {
  TempDir dir;
  const std::string richardson = replaced(replaced(kItem, "across_runs: loglog_slope", "across_runs: richardson_order"),
                                          "tolerance: {absolute: 0.1}", "tolerance: {lower_bound: true}");
  // Three full runs but only two quick runs: an observed order needs three in both modes.
  EXPECT_NE(loadError(richardson).find("at least 3 runs"), std::string::npos) << loadError(richardson);
  const std::string three = replaced(replaced(richardson, "quick_values: [1.0e6, 4.0e6]", "quick_values: [1.0e6, 2.0e6, 4.0e6]"),
                                     "values: [1.0e6, 2.0e6, 4.0e6]", "values: [1.0e6, 2.0e6, 4.0e6]");
  const Item item = loadItem(itemDir(dir, three));
  EXPECT_EQ(item.quantities[1].across, AcrossRuns::RichardsonOrder);
  EXPECT_TRUE(item.quantities[1].tolerance.lowerBound);
  // Ratios 2 and 1.5: no constant refinement.
  EXPECT_NE(loadError(replaced(replaced(three, "quick_values: [1.0e6, 2.0e6, 4.0e6]", "quick_values: [1.0e6, 2.0e6, 3.0e6]"),
                               "values: [1.0e6, 2.0e6, 4.0e6]", "values: [1.0e6, 2.0e6, 3.0e6]"))
                .find("constant refinement ratio"),
            std::string::npos);
  const std::string increment = replaced(richardson, "across_runs: richardson_order", "across_runs: min_increment");
  EXPECT_EQ(loadItem(itemDir(dir, increment)).quantities[1].across, AcrossRuns::MinIncrement);
  // The gap closed needs a first, a second and a last run in both modes, as the observed order.
  const std::string gap = replaced(richardson, "across_runs: richardson_order", "across_runs: gap_closed");
  EXPECT_NE(loadError(gap).find("at least 3 runs"), std::string::npos) << loadError(gap);
  EXPECT_EQ(loadItem(itemDir(dir, replaced(three, "across_runs: richardson_order", "across_runs: gap_closed"))).quantities[1].across,
            AcrossRuns::GapClosed);
  EXPECT_NE(loadError(replaced(richardson, "{lower_bound: true}", "{lower_bound: true, absolute: 0.1}")).find("lower_bound alone"),
            std::string::npos);
}

TEST(ValidationSpec, QuickToleranceReplacesTheToleranceInQuickMode) {
  TempDir dir;
  const Item item = loadItem(itemDir(dir, replaced(kItem, "    tolerance: {relative: 0.01}", "    tolerance: {relative: 0.01}\n    quick_tolerance: {relative: 0.05}")));
  EXPECT_DOUBLE_EQ(item.quantities[0].toleranceFor(false).value, 0.01);
  EXPECT_DOUBLE_EQ(item.quantities[0].toleranceFor(true).value, 0.05);
  EXPECT_DOUBLE_EQ(item.quantities[1].toleranceFor(true).value, 0.1);  // none given: the tolerance
}

TEST(ValidationSpec, OverridesFollowKeyPathsIntoMapsAndLists) {
  const std::string text = applyOverrides(
      "time: {end: 1.0}\nmaterials:\n  - {name: a, restitution: 0.5}\n  - {name: b}\ninsertion:\n  - {velocity: [0, 0, 1]}\n",
      {{"time.end", "0.25"}, {"materials[1].restitution", "0.9"}, {"insertion[0].velocity[2]", "-3"}, {"output.interval", "0.01"}},
      "test");
  gf::Params p = gf::Params::loadString(text, "test");
  EXPECT_DOUBLE_EQ(p.section({"time"}).real({"end"}), 0.25);
  auto materials = p.list({"materials"});
  ASSERT_EQ(materials.size(), 2u);
  EXPECT_DOUBLE_EQ(materials[0].real({"restitution"}), 0.5);
  EXPECT_DOUBLE_EQ(materials[1].real({"restitution"}), 0.9);
  EXPECT_DOUBLE_EQ(p.list({"insertion"})[0].vec3({"velocity"}).z, -3.0);
  EXPECT_DOUBLE_EQ(p.section({"output"}).real({"interval"}), 0.01);
  EXPECT_THROW(applyOverrides("materials: [{name: a}]\n", {{"materials[3].density", "1"}}, "test"), gf::CaseError);
  EXPECT_THROW(applyOverrides("time: 3\n", {{"time.end", "1"}}, "test"), gf::CaseError);
}

TEST(ValidationSpec, ColumnNamesIgnoreUnits) {
  const std::vector<std::string> header = {"time [s]", "vz [m/s]", "plain"};
  EXPECT_EQ(columnIndex(header, "vz"), 1);
  EXPECT_EQ(columnIndex(header, "plain"), 2);
  EXPECT_EQ(columnIndex(header, "v"), -1);
  EXPECT_EQ(columnUnit(header[1]), "m/s");
  EXPECT_EQ(columnUnit(header[2]), "");
}

TEST(ValidationSpec, ProfileWithReferencePointsAndSharedFigure) {
  const std::string profile = R"yaml(title: Profiles
quantities:
  - name: u on x = 0.5
    monitor: line
    column: velocity_x
    x_column: y
    operation: profile
    reference:
      points: [[0.9766, 0.84123], [0.0547, -0.03717], [0.5, -0.20581]]
      source: "Ghia, Ghia & Shin (1982), Table I"
    tolerance: {absolute: 0.01}
    plot: {figure: centrelines, swap_axes: true, reference_label: "Ghia et al. (1982)"}
  - name: v on y = 0.5
    monitor: line_x
    column: velocity_y
    x_column: x
    operation: profile
    reference: {file: ref.csv, x: E, y: top, source: "made up"}
    tolerance: {absolute: 0.01}
    plot: {figure: centrelines}
)yaml";
  TempDir dir;
  const Item item = loadItem(itemDir(dir, profile));
  ASSERT_EQ(item.quantities.size(), 2u);
  const Quantity& u = item.quantities[0];
  EXPECT_EQ(u.operation, Operation::Profile);
  EXPECT_EQ(u.xColumn, "y");
  EXPECT_EQ(u.reference.data.x, (std::vector<double>{0.0547, 0.5, 0.9766}));  // sorted by x
  EXPECT_EQ(u.reference.data.y, (std::vector<double>{-0.03717, -0.20581, 0.84123}));
  EXPECT_EQ(u.plot.figure, "centrelines");
  EXPECT_TRUE(u.plot.swapAxes);
  EXPECT_EQ(u.plot.referenceLabel, "Ghia et al. (1982)");
  EXPECT_FALSE(item.quantities[1].plot.swapAxes);
  EXPECT_EQ(item.quantities[1].plot.referenceLabel, "reference");
  EXPECT_EQ(item.quantities[1].reference.data.x.size(), 2u);

  EXPECT_NE(loadError(replaced(profile, "    x_column: y\n", "")).find("profile without x_column"), std::string::npos);
  EXPECT_NE(loadError(replaced(profile, "reference: {file: ref.csv, x: E, y: top, source: \"made up\"}",
                               "reference: {value: 1.0, source: \"made up\"}"))
                .find("a single value for operation: profile"),
            std::string::npos);
  EXPECT_NE(loadError(replaced(profile, "[0.5, -0.20581]]", "[0.5]]")).find("[x, y] pairs"), std::string::npos);
  EXPECT_NE(loadError(replaced(profile, "source: \"Ghia, Ghia & Shin (1982), Table I\"", "value: 1.0\n      source: \"x\""))
                .find("exactly one of them"),
            std::string::npos);
  // Points for a single number without a sweep make no sense either.
  EXPECT_NE(loadError(replaced(profile, "    operation: profile\n    reference:\n      points",
                               "    operation: final\n    reference:\n      points"))
                .find("reference points for a single number"),
            std::string::npos);
}
