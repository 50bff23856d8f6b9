#pragma once
// Presenting validation results: the console table, results.csv and docs/validation.md (with
// date, commit, machine) plus the README summary between markers.
#include <string>
#include <vector>

#include "app/validation_results.hpp"

namespace gf::app::validation {

/// Aligned console table: case, quantity, reference, grainflow, error, tolerance, result (+ notes of failures).
std::string textTable(const std::vector<Row>& rows);
/// Machine-readable results, one row per comparison.
std::string resultsCsv(const std::vector<Row>& rows);

/// Writes <docsDirectory>/validation.md and copies the figures to <docsDirectory>/img/; updates the
/// summary between <!-- validation-summary:begin/end --> in <repository>/README.md if present.
void writeDocs(const std::string& docsDirectory, const std::string& repository, const std::vector<Item>& items,
               const std::vector<std::vector<Row>>& rowsPerItem, const std::vector<ItemOutcome>& outcomes, double wall, int threads);

}  // namespace gf::app::validation
