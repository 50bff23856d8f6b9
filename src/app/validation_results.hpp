#pragma once
// From a finished run to comparison rows: extraction of each quantity from the monitor CSV
// (operations of validation_extract.hpp) and its comparison with the reference.
#include <optional>
#include <string>
#include <vector>

#include "app/validation_extract.hpp"
#include "app/validation_spec.hpp"

namespace gf::app::validation {

struct Extracted {
  std::optional<double> value;  // single-number operations
  Series curve;                 // the compared (operation: curve or profile) or plotted series
  std::optional<double> profileTime;  // operation: profile: the sample time of the profile
  std::string xLabel, yLabel;   // CSV headers with units
  std::string problem;          // why nothing could be extracted
};

struct Row {
  std::string item, runLabel, quantity, operation;
  std::optional<Comparison> comparison;
  Tolerance tolerance;
  std::string note;  // curve: worst point; failure reason
  std::optional<double> at;  // profile: the reference point's position
  bool pass() const { return comparison && comparison->pass; }
};

/// Per item: wall time of its runs and the figures made.
struct ItemOutcome {
  double wallSeconds = 0.0;
  std::vector<std::string> plots;  // PNG paths
  bool skipped = false;
};

/// "item" or "item (key = value)".
std::string caseLabel(const Item& item, const RunPoint& run);
/// Lower-case file-name form of a quantity name ("height z(t)" -> "height_z_t").
std::string slug(const std::string& text);

/// Reads <runDirectory>/<monitor>.csv and applies the quantity's window, operation, scale and offset.
/// Problems (missing file or column, no crossing) are reported in Extracted::problem, not thrown.
Extracted extract(const Quantity& q, const std::string& runDirectory);

/// The comparison rows of one quantity over the runs of an item (one per run, or one for
/// across_runs); runFailures[k] is non-empty when run k diverged.
std::vector<Row> compareQuantity(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs,
                                 const std::vector<Extracted>& extracted, const std::vector<std::string>& runFailures);

}  // namespace gf::app::validation
