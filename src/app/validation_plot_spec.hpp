#pragma once
// The figures of validation quantities as JSON specs for tools/plot.py (which only draws): per
// quantity a panel with the computed curve(s) or values, the reference points/curve/line, axis
// labels and the compared numbers; quantities of an item with the same `plot.figure` share one
// figure, a panel each (e.g. the two centreline profiles of a cavity).
#include <string>
#include <vector>

#include "app/validation_results.hpp"

namespace gf::app::validation {

struct PlotSeries {
  std::string label;
  std::string style;       // line, points, linepoints, dashed
  bool reference = false;  // drawn in black
  std::vector<double> x, y;
};

struct Panel {
  std::string title;  // the quantity's name
  std::string xLabel, yLabel;
  bool logX = false, logY = false, swapAxes = false;
  std::vector<PlotSeries> series;
  std::string note;  // the compared numbers, shown under the figure
};

/// The panel of one quantity over the runs of its item.
Panel plotPanel(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs, const std::vector<Extracted>& extracted,
                const std::vector<Row>& rows);

/// Writes <itemDirectory>/<item>_<slug(name)>.plot.json, a figure of the panels side by side (one
/// panel: titled "<item title>: <panel title>"; several: the item title above them), appends its
/// path to `specs` and returns the PNG path the script will write.
std::string writePlotSpec(const Item& item, const std::string& name, const std::vector<Panel>& panels, const std::string& itemDirectory,
                          std::vector<std::string>& specs);

/// The figures of an item: one per quantity without `plot.figure`, one per figure name (in the
/// order of first use) for the others; returns the PNG paths. rowsPerQuantity[q] are the rows of
/// quantity q, extracted[q][run] its extractions.
std::vector<std::string> writeItemPlotSpecs(const Item& item, const std::vector<Quantity>& quantities, const std::vector<RunPoint>& runs,
                                            const std::vector<std::vector<Extracted>>& extracted,
                                            const std::vector<std::vector<Row>>& rowsPerQuantity, const std::string& itemDirectory,
                                            std::vector<std::string>& specs);

}  // namespace gf::app::validation
