#pragma once
// `grainflow validate [--quick] [NAME...]`: runs the validation items under validation/ (data:
// validation.yaml + case + reference), extracts the compared quantities from the monitor CSVs,
// prints the comparison table with progress and ETA, writes results.csv and plots, and in full
// mode over all items regenerates docs/validation.md (+ docs/img/). Format: docs/validation-format.md.
#include <string>
#include <vector>

namespace gf::app {

/// Exit code when every item ran but at least one comparison failed.
inline constexpr int kExitValidationFailed = 6;

struct ValidateOptions {
  bool quick = false;
  std::vector<std::string> names;   // empty = all items
  std::string validationDirectory;  // "" = ./validation if present, else the source tree's
  std::string outputDirectory = "output/validation";
  std::string docsDirectory;        // "" = <validation directory>/../docs
  bool writeDocs = true;            // full mode over all items only
  bool plots = true;
  int threads = 0;
};

/// Runs the selected items; returns an exit code (0 = all passed).
int runValidate(const ValidateOptions& options);

}  // namespace gf::app
