#pragma once
// Plotting through tools/plot.py (python3 + matplotlib from Debian's python3-matplotlib).
// The C++ side decides what is plotted; the script only draws. Without python3/matplotlib the
// numbers are still produced and kPlotInstallHint says how to get the plots.
#include <string>
#include <vector>

namespace gf::app {

inline constexpr const char* kPlotInstallHint =
    "install the plotting part with: apt-get install python3-matplotlib (or run scripts/setup.sh)";

struct PlotTool {
  std::string python;   // interpreter that imports matplotlib ("" if none)
  std::string script;   // tools/plot.py ("" if not found)
  std::string problem;  // why plotting is unavailable ("" if available)
  bool available() const { return problem.empty(); }
};

/// Finds tools/plot.py (GRAINFLOW_PLOT_SCRIPT, <repositoryHint>/tools, next to the executable,
/// the source tree) and a Python with matplotlib (GRAINFLOW_PYTHON if set, else python3, /usr/bin/python3).
PlotTool findPlotTool(const std::string& repositoryHint = "");

/// Runs the script with the given arguments; returns its exit status (0 = success).
int runPlotScript(const PlotTool& tool, const std::vector<std::string>& arguments);

/// Quotes a word for /bin/sh.
std::string shellQuote(const std::string& word);

/// `grainflow plot OUTPUT_DIR`: one PNG per monitor CSV of a run, next to the CSVs. Returns an exit code.
int plotRunOutput(const std::string& outputDirectory);

}  // namespace gf::app
