#pragma once
// A validation item as data: validation/<name>/validation.yaml (format: docs/validation-format.md)
// next to the case file it runs and its reference data. Loading checks every key strictly
// (unknown keys, wrong types, missing files and columns give file:line errors), so a broken
// item fails before any simulation starts.
#include <optional>
#include <string>
#include <vector>

#include "app/validation_extract.hpp"

namespace gf::app::validation {

/// Replace the value at a key path ("time.end", "materials[0].restitution") by a YAML value.
struct Override {
  std::string path;
  std::string yaml;  // the value as YAML text
};

/// One run of an item: its x value in sweep plots, a label and the case overrides it applies.
struct RunPoint {
  double x = 0.0;
  std::string label;  // "materials[0].restitution = 0.5", or "" for an item without a sweep
  std::vector<Override> overrides;
};

/// Profile: the column over x_column (a position) in the rows of the last sample time of a
/// long-format CSV (fluid_line_profile), compared at each reference point.
enum class Operation { Final, Initial, Min, Max, Mean, ValueAt, FirstCrossing, DurationAbove, Ratio, Curve, Profile };
/// One comparison for a whole sweep: log-log slope, observed (Richardson) order of the last three
/// runs, the smallest increase between consecutive runs, or the share of the first run's distance
/// from the last that the second run closes.
enum class AcrossRuns { None, LogLogSlope, RichardsonOrder, MinIncrement, GapClosed };
/// Name in validation.yaml <-> across-runs kind.
const std::vector<std::pair<std::string, AcrossRuns>>& acrossRunsNames();
std::string acrossRunsName(AcrossRuns a);

/// Name in validation.yaml <-> operation.
const std::vector<std::pair<std::string, Operation>>& operationNames();
std::string operationName(Operation op);

struct Reference {
  std::optional<double> value;  // a single number, or ...
  std::string file;             // ... a CSV (path relative to the item directory) with columns x, y, or ...
  std::string xColumn, yColumn;
  Series data;                  // ... points (x, y) given in validation.yaml: the CSV columns or the points, sorted by x
  std::string source;           // paper/table/figure, seed file + line, or the formula it was computed from
};

struct PlotSpec {
  std::string xLabel, yLabel;
  bool logX = false, logY = false;
  std::string referenceStyle = "auto";  // auto (points for curves and profiles, line for sweeps), points, line
  std::string figure;                   // quantities of an item with the same figure share one PNG, a panel each
  bool swapAxes = false;                // x_column on the vertical axis (a profile along a vertical line, u(y))
  std::string referenceLabel = "reference";  // legend entry of the reference (e.g. the paper)
};

struct Quantity {
  std::string name;
  std::string monitor;            // CSV file (without .csv) in the run's output directory
  std::string column;             // column name without its unit
  std::string xColumn = "time";   // abscissa for windows, crossings and curves
  Operation operation = Operation::Final;
  Operation numerator = Operation::Final, denominator = Operation::Initial;  // for ratio
  std::optional<std::pair<double, double>> window;
  double threshold = 0.0;  // first_crossing, duration_above
  double at = 0.0;         // value_at
  double scale = 1.0, offset = 0.0;  // reported value = scale * extracted + offset
  AcrossRuns across = AcrossRuns::None;
  Reference reference;
  Tolerance tolerance;
  std::optional<Tolerance> quickTolerance;  // replaces `tolerance` in --quick mode (coarser quick settings)
  PlotSpec plot;
  const Tolerance& toleranceFor(bool quick) const { return quick && quickTolerance ? *quickTolerance : tolerance; }
};

struct Item {
  std::string name;       // directory name
  std::string directory;  // absolute or as given
  std::string title, description;
  std::string caseFile;   // path
  std::vector<Override> quickOverrides;
  bool skipQuick = false;
  /// report_quick: the full report (`grainflow validate`, all items) runs this item with its --quick
  /// settings and tolerances, because its full run takes hours; `grainflow validate NAME` runs it in full.
  bool reportQuick = false;
  std::string sweepKey, sweepLabel;
  std::vector<RunPoint> runs, quickRuns;  // one entry without overrides when there is no sweep
  std::vector<Quantity> quantities;

  const std::vector<RunPoint>& runsFor(bool quick) const { return quick ? quickRuns : runs; }
};

/// Names of the items (sub-directories holding validation.yaml), sorted.
std::vector<std::string> listItems(const std::string& validationDirectory);
/// Loads and checks <directory>/validation.yaml, its reference files and that its case file exists. Throws CaseError.
Item loadItem(const std::string& directory);

/// Applies overrides to YAML case text; returns the new text. Throws CaseError (naming `origin`)
/// when a path cannot be followed (e.g. an index past the end of a list).
std::string applyOverrides(const std::string& caseText, const std::vector<Override>& overrides,
                           const std::string& origin);

/// The column `name` of a CSV header entry "name [unit]" (exact name match); -1 if absent.
int columnIndex(const std::vector<std::string>& header, const std::string& name);
/// The unit of a header entry ("m/s" of "vz [m/s]"), "" if none.
std::string columnUnit(const std::string& headerEntry);

}  // namespace gf::app::validation
