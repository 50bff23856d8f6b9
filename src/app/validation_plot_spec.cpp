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

std::string seriesJson(const PlotSeries& s) {
  const std::size_t stride = std::max<std::size_t>(1, s.x.size() / 4000);
  return fmt::format("{{\"label\": {}, \"style\": {}, \"reference\": {}, \"x\": {}, \"y\": {}}}", jsonString(s.label), jsonString(s.style),
                     s.reference ? "true" : "false", jsonNumbers(s.x, stride), jsonNumbers(s.y, stride));
}

std::string panelJson(const Panel& p) {
  std::string out = fmt::format(
      "{{\"title\": {}, \"x_label\": {}, \"y_label\": {}, \"log_x\": {}, \"log_y\": {}, \"swap_axes\": {}, \"series\": [",
      jsonString(p.title), jsonString(p.xLabel), jsonString(p.yLabel), p.logX ? "true" : "false", p.logY ? "true" : "false",
      p.swapAxes ? "true" : "false");
  for (std::size_t i = 0; i < p.series.size(); ++i) out += (i ? ", " : "") + seriesJson(p.series[i]);
  return out + "]}";
}

std::string formatError(double error, const Tolerance& t) {
  return t.relative ? fmt::format("{:.3g} %", 100.0 * error) : fmt::format("{:.3g}", error);
}

/// Profile: the computed profile of each run as a line, the reference points on top; the note
/// gives per run the largest deviation and where.
Panel profilePanel(const Quantity& q, const std::vector<RunPoint>& runs, const std::vector<Extracted>& extracted,
                   const std::vector<Row>& rows, Panel panel) {
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const Extracted& e = extracted[k];
    if (e.curve.x.empty()) continue;
    std::string label = runs[k].label.empty() ? "grainflow" : "grainflow, " + runs[k].label;
    if (e.profileTime) label += fmt::format(" (t = {:g} s)", *e.profileTime);
    panel.series.push_back({label, "line", false, e.curve.x, e.curve.y});
    const Row* worst = nullptr;
    std::size_t points = 0;
    for (const Row& r : rows)
      if (r.runLabel == runs[k].label && r.comparison && r.at) {
        ++points;
        if (!worst || std::abs(r.comparison->error) > std::abs(worst->comparison->error)) worst = &r;
      }
    if (worst)
      panel.note += fmt::format("{}{}{}: largest deviation {} (at {} = {:g}; {} points compared, tolerance {})", panel.note.empty() ? "" : "\n", q.name,
                                runs[k].label.empty() ? "" : ", " + runs[k].label, formatError(worst->comparison->error, q.tolerance),
                                q.xColumn, *worst->at, points, formatError(q.tolerance.value, q.tolerance));
  }
  for (const Row& r : rows)
    if (!r.comparison && !r.note.empty()) panel.note += fmt::format("{}{}: {}", panel.note.empty() ? "" : "\n", q.name, r.note);
  if (!q.reference.data.x.empty())
    panel.series.push_back({q.plot.referenceLabel, q.plot.referenceStyle == "line" ? "dashed" : "points", true, q.reference.data.x,
                            q.reference.data.y});
  return panel;
}

bool yIsColumnValue(const Quantity& q) {
  return q.operation != Operation::FirstCrossing && q.operation != Operation::DurationAbove && q.operation != Operation::Ratio;
}

}  // namespace

Panel plotPanel(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs, const std::vector<Extracted>& extracted,
                const std::vector<Row>& rows) {
  Panel panel;
  panel.title = q.name;
  panel.xLabel = q.plot.xLabel;
  panel.yLabel = q.plot.yLabel;
  panel.logX = q.plot.logX;
  panel.logY = q.plot.logY;
  panel.swapAxes = q.plot.swapAxes;
  const Extracted* first = nullptr;
  for (const Extracted& e : extracted)
    if (!e.xLabel.empty()) first = first ? first : &e;
  if (first) {
    if (panel.xLabel.empty()) panel.xLabel = first->xLabel;
    if (panel.yLabel.empty()) panel.yLabel = first->yLabel;
  }
  if (q.operation == Operation::Profile) return profilePanel(q, runs, extracted, rows, panel);
  std::vector<PlotSeries>& series = panel.series;
  std::string& note = panel.note;
  const bool sweep = runs.size() > 1 || !item.sweepKey.empty();
  for (const Row& r : rows)
    if (r.comparison)
      note += fmt::format("{}{}: grainflow {:.5g}, reference {:.5g}{}", note.empty() ? "" : "\n",
                          q.across == AcrossRuns::LogLogSlope       ? "observed log-log slope"
                          : q.across == AcrossRuns::RichardsonOrder ? "observed order (last three runs)"
                          : q.across == AcrossRuns::MinIncrement    ? "smallest increase between runs"
                          : q.across == AcrossRuns::GapClosed       ? "share of the first run's gap to the last closed by the second"
                          : r.runLabel.empty()                      ? q.name
                                                                    : r.runLabel,
                          r.comparison->computed, r.comparison->reference, q.operation == Operation::Curve ? " (worst point)" : "");
  if (q.operation == Operation::Curve || !sweep) {
    // The monitor curve(s) of each run; the reference points or value on top.
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (!extracted[k].curve.x.empty())
        series.push_back({runs[k].label.empty() ? "grainflow" : "grainflow, " + runs[k].label, "line", false, extracted[k].curve.x,
                          extracted[k].curve.y});
    if (!q.reference.data.x.empty()) {
      series.push_back({q.plot.referenceLabel, q.plot.referenceStyle == "line" ? "dashed" : "points", true, q.reference.data.x, q.reference.data.y});
    } else if (q.reference.value && yIsColumnValue(q) && first && !first->curve.x.empty()) {
      series.push_back({fmt::format("{} ({})", q.plot.referenceLabel, operationName(q.operation)), "dashed", true,
                        {first->curve.x.front(), first->curve.x.back()}, {*q.reference.value, *q.reference.value}});
    }
  } else {
    // One number per run against the swept value.
    PlotSeries computed{"grainflow", "linepoints", false, {}, {}};
    for (std::size_t k = 0; k < runs.size(); ++k)
      if (extracted[k].value) {
        computed.x.push_back(runs[k].x);
        computed.y.push_back(q.across == AcrossRuns::LogLogSlope ? std::abs(*extracted[k].value) : *extracted[k].value);
      }
    if (q.plot.xLabel.empty()) panel.xLabel = item.sweepLabel;
    if (q.plot.yLabel.empty()) panel.yLabel = q.name;
    if (q.across == AcrossRuns::RichardsonOrder) {
      // |f_k - f_k+1| at the coarser x_k: falls with slope p towards the finer runs.
      PlotSeries differences{"grainflow |f(run k) - f(run k+1)|", "linepoints", false, {}, {}};
      for (std::size_t k = 0; k + 1 < computed.x.size(); ++k) {
        differences.x.push_back(computed.x[k]);
        differences.y.push_back(std::abs(computed.y[k] - computed.y[k + 1]));
      }
      computed = differences;
      panel.logX = panel.logY = true;
      if (!computed.x.empty() && q.reference.value) {
        const double p = *q.reference.value * (computed.x.back() > computed.x.front() ? -1.0 : 1.0);
        PlotSeries slope{fmt::format("order {:g} ({})", *q.reference.value, q.plot.referenceLabel), "dashed", true, computed.x, {}};
        for (double x : computed.x) slope.y.push_back(computed.y.front() * std::pow(x / computed.x.front(), p));
        series.push_back(slope);
      }
    } else if (q.across == AcrossRuns::MinIncrement || q.across == AcrossRuns::GapClosed) {
      // the values themselves; no reference line (the bound is on their differences)
    } else if (q.across == AcrossRuns::LogLogSlope && computed.x.size() >= 1 && q.reference.value) {
      PlotSeries slope{fmt::format("slope {:g} ({})", *q.reference.value, q.plot.referenceLabel), "dashed", true, computed.x, {}};
      for (double x : computed.x) slope.y.push_back(computed.y.front() * std::pow(x / computed.x.front(), *q.reference.value));
      series.push_back(slope);
    } else if (!q.reference.data.x.empty()) {
      series.push_back({q.plot.referenceLabel, q.plot.referenceStyle == "points" ? "points" : "dashed", true, q.reference.data.x,
                        q.reference.data.y});
    } else if (q.reference.value && !computed.x.empty()) {
      const auto [lo, hi] = std::minmax_element(computed.x.begin(), computed.x.end());
      series.push_back({q.plot.referenceLabel, "dashed", true, {*lo, *hi}, {*q.reference.value, *q.reference.value}});
    }
    series.insert(series.begin(), computed);
  }
  return panel;
}

std::string writePlotSpec(const Item& item, const std::string& name, const std::vector<Panel>& panels, const std::string& itemDirectory,
                          std::vector<std::string>& specs) {
  const std::string base = fmt::format("{}_{}", item.name, slug(name));
  const std::string png = (fs::path(itemDirectory) / (base + ".png")).string();
  const std::string title = panels.size() == 1 ? fmt::format("{}: {}", item.title, panels.front().title) : item.title;
  std::string note;
  for (const Panel& p : panels)
    if (!p.note.empty()) note += (note.empty() ? "" : "\n") + p.note;
  std::string json = fmt::format("{{\"output\": {}, \"title\": {}, \"note\": {}, \"panels\": [", jsonString(png), jsonString(title), jsonString(note));
  for (std::size_t i = 0; i < panels.size(); ++i) {
    Panel p = panels[i];
    if (panels.size() == 1) p.title.clear();  // in the figure title already
    json += (i ? ", " : "") + panelJson(p);
  }
  json += "]}\n";
  const std::string specFile = (fs::path(itemDirectory) / (base + ".plot.json")).string();
  io::writeFileAtomically(specFile, json);
  specs.push_back(specFile);
  return png;
}

std::vector<std::string> writeItemPlotSpecs(const Item& item, const std::vector<Quantity>& quantities, const std::vector<RunPoint>& runs,
                                            const std::vector<std::vector<Extracted>>& extracted,
                                            const std::vector<std::vector<Row>>& rowsPerQuantity, const std::string& itemDirectory,
                                            std::vector<std::string>& specs) {
  std::vector<std::string> pngs, figures;
  std::vector<std::vector<Panel>> panels;
  for (std::size_t q = 0; q < quantities.size(); ++q) {
    const std::string figure = quantities[q].plot.figure.empty() ? quantities[q].name : quantities[q].plot.figure;
    auto it = std::find(figures.begin(), figures.end(), figure);
    if (it == figures.end() || quantities[q].plot.figure.empty()) {
      figures.push_back(figure);
      panels.emplace_back();
      it = figures.end() - 1;
    }
    panels[static_cast<std::size_t>(it - figures.begin())].push_back(plotPanel(item, quantities[q], runs, extracted[q], rowsPerQuantity[q]));
  }
  for (std::size_t f = 0; f < figures.size(); ++f) pngs.push_back(writePlotSpec(item, figures[f], panels[f], itemDirectory, specs));
  return pngs;
}

}  // namespace gf::app::validation
