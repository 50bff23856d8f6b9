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

/// What the report was made from, read before the first run (a commit made while the runs go
/// must not be named): HEAD and the paths whose content differs from it, tracked or untracked
/// (ignored ones such as build/ and output/ do not count), except the files the report rewrites
/// itself (docs/validation.md, docs/img/, README.md), so that a rerun does not flag its own output.
struct Provenance {
  std::string commit;                // short hash; "" outside a git work tree
  std::vector<std::string> changes;  // `git status --porcelain` lines
};
Provenance treeProvenance(const std::string& repository);

/// Writes <docsDirectory>/validation.md and copies the figures to <docsDirectory>/img/, removing the
/// figures the previous report showed and this one does not (unless README.md shows them); updates
/// the summary between <!-- validation-summary:begin/end --> in <repository>/README.md if present.
void writeDocs(const std::string& docsDirectory, const std::string& repository, const std::vector<Item>& items,
               const std::vector<std::vector<Row>>& rowsPerItem, const std::vector<ItemOutcome>& outcomes, double wall, int threads,
               const Provenance& provenance);

}  // namespace gf::app::validation
