#pragma once
// The figure of one validation quantity as a JSON spec for tools/plot.py (which only draws):
// computed curve(s) or values, reference points/curve/line, axis labels, the compared numbers.
#include <string>
#include <vector>

#include "app/validation_results.hpp"

namespace gf::app::validation {

/// Writes <itemDirectory>/<item>_<quantity>.plot.json, appends its path to `specs` and returns the PNG
/// path the script will write.
std::string writePlotSpec(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs,
                          const std::vector<Extracted>& extracted, const std::vector<Row>& rows, const std::string& itemDirectory,
                          std::vector<std::string>& specs);

}  // namespace gf::app::validation
