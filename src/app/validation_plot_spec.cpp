#include "app/validation_plot_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "io/atomic_file.hpp"

namespace gf::app::validation {

namespace fs = std::filesystem;

namespace {

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string jsonNumbers(const std::vector<double>& values, std::size_t stride) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); i += stride) {
    if (i > 0) out += ",";
    out += std::isfinite(values[i]) ? fmt::format("{:.10g}", values[i]) : "NaN";
  }
  if (stride > 1 && (values.size() - 1) % stride != 0) out += fmt::format(",{:.10g}", values.back());
  return out + "]";
}

struct PlotSeries {
  std::string label, style;  // style: line, points, linepoints, dashed
  std::vector<double> x, y;
};

std::string plotSpecJson(const std::string& output, const std::string& title, const std::string& xLabel, const std::string& yLabel,
                         const PlotSpec& axes, const std::string& note, const std::vector<PlotSeries>& series) {
  std::string out = fmt::format("{{\"output\": {}, \"title\": {}, \"x_label\": {}, \"y_label\": {}, \"log_x\": {}, \"log_y\": {}, \"note\": {}, \"series\": [",
                                jsonString(output), jsonString(title), jsonString(xLabel), jsonString(yLabel),
                                axes.logX ? "true" : "false", axes.logY ? "true" : "false", jsonString(note));
  for (std::size_t i = 0; i < series.size(); ++i) {
    const std::size_t stride = std::max<std::size_t>(1, series[i].x.size() / 4000);
    out += fmt::format("{}{{\"label\": {}, \"style\": {}, \"x\": {}, \"y\": {}}}", i ? ", " : "", jsonString(series[i].label),
                       jsonString(series[i].style), jsonNumbers(series[i].x, stride), jsonNumbers(series[i].y, stride));
  }
  return out + "]}\n";
}

bool yIsColumnValue(const Quantity& q) {
  return q.operation != Operation::FirstCrossing && q.operation != Operation::DurationAbove && q.operation != Operation::Ratio;
}

}  // namespace

std::string writePlotSpec(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs,
                          const std::vector<Extracted>& extracted, const std::vector<Row>& rows, const std::string& itemDirectory,
                          std::vector<std::string>& specs) {
  std::string png = (fs::path(itemDirectory) / fmt::format("{}_{}.png", item.name, slug(q.name))).string();
  std::vector<PlotSeries> series;
  std::string xLabel = q.plot.xLabel, yLabel = q.plot.yLabel, note;
  PlotSpec axes = q.plot;
  const bool sweep = runs.size() > 1 || !item.sweepKey.empty();
  const Extracted* first = nullptr;
  for (const Extracted& e : extracted)
    if (!e.xLabel.empty()) first = first ? first : &e;
  for (const Row& r : rows)
    if (r.comparison)
      note += fmt::format("{}{}: grainflow {:.5g}, reference {:.5g}{}", note.empty() ? "" : "\n",
                          q.across == AcrossRuns::LogLogSlope       ? "observed log-log slope"
                          : q.across == AcrossRuns::RichardsonOrder ? "observed order (last three runs)"
                          : q.across == AcrossRuns::MinIncrement    ? "smallest increase between runs"
                          : r.runLabel.empty()                      ? q.name
                                                                    : r.runLabel,
                          r.comparison->computed, r.comparison->reference, q.operation == Operation::Curve ? " (worst point)" : "");
  if (q.operation == Operation::Curve || !sweep) {
    // The monitor curve(s) of each run; the reference points or value on top.
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (!extracted[k].curve.x.empty())
        series.push_back({runs[k].label.empty() ? "grainflow" : "grainflow, " + runs[k].label, "line", extracted[k].curve.x, extracted[k].curve.y});
    if (first) {
      if (xLabel.empty()) xLabel = first->xLabel;
      if (yLabel.empty()) yLabel = first->yLabel;
    }
    if (!q.reference.data.x.empty()) {
      series.push_back({"reference", q.plot.referenceStyle == "line" ? "dashed" : "points", q.reference.data.x, q.reference.data.y});
    } else if (q.reference.value && yIsColumnValue(q) && first && !first->curve.x.empty()) {
      series.push_back({"reference " + operationName(q.operation), "dashed", {first->curve.x.front(), first->curve.x.back()},
                        {*q.reference.value, *q.reference.value}});
    }
  } else {
    // One number per run against the swept value.
    PlotSeries computed{"grainflow", "linepoints", {}, {}};
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (extracted[k].value) {
        computed.x.push_back(runs[k].x);
        computed.y.push_back(q.across == AcrossRuns::LogLogSlope ? std::abs(*extracted[k].value) : *extracted[k].value);
      }
    if (xLabel.empty()) xLabel = item.sweepLabel;
    if (yLabel.empty()) yLabel = q.name;
    if (q.across == AcrossRuns::RichardsonOrder) {
      // |f_k - f_k+1| at the coarser x_k: falls with slope p towards the finer runs.
      PlotSeries differences{"grainflow |f(run k) - f(run k+1)|", "linepoints", {}, {}};
      for (std::size_t k = 0; k + 1 < computed.x.size(); ++k) {
        differences.x.push_back(computed.x[k]);
        differences.y.push_back(std::abs(computed.y[k] - computed.y[k + 1]));
      }
      computed = differences;
      axes.logX = axes.logY = true;
      if (!computed.x.empty() && q.reference.value) {
        const double p = *q.reference.value * (computed.x.back() > computed.x.front() ? -1.0 : 1.0);
        PlotSeries slope{fmt::format("order {:g} (reference)", *q.reference.value), "dashed", computed.x, {}};
        for (double x : computed.x) slope.y.push_back(computed.y.front() * std::pow(x / computed.x.front(), p));
        series.push_back(slope);
      }
    } else if (q.across == AcrossRuns::MinIncrement) {
      // the values themselves; no reference line (the bound is on their differences)
    } else if (q.across == AcrossRuns::LogLogSlope && computed.x.size() >= 1 && q.reference.value) {
      PlotSeries slope{fmt::format("slope {:g} (reference)", *q.reference.value), "dashed", computed.x, {}};
      for (double x : computed.x) slope.y.push_back(computed.y.front() * std::pow(x / computed.x.front(), *q.reference.value));
      series.push_back(slope);
    } else if (!q.reference.data.x.empty()) {
      series.push_back({"reference", q.plot.referenceStyle == "points" ? "points" : "dashed", q.reference.data.x, q.reference.data.y});
    } else if (q.reference.value && !computed.x.empty()) {
      const auto [lo, hi] = std::minmax_element(computed.x.begin(), computed.x.end());
      series.push_back({"reference", "dashed", {*lo, *hi}, {*q.reference.value, *q.reference.value}});
    }
    series.insert(series.begin(), computed);
  }
  const std::string specFile = (fs::path(itemDirectory) / fmt::format("{}_{}.plot.json", item.name, slug(q.name))).string();
  io::writeFileAtomically(specFile, plotSpecJson(png, fmt::format("{}: {}", item.title, q.name), xLabel, yLabel, axes, note, series));
  specs.push_back(specFile);
  return png;
}

}  // namespace gf::app::validation
