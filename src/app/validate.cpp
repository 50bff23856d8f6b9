#include "app/validate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "app/cli.hpp"
#include "app/plot.hpp"
#include "app/simulation.hpp"
#include "app/validation_spec.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_series.hpp"

namespace gf::app {

namespace fs = std::filesystem;
using namespace validation;

namespace {

// ------------------------------------------------------------------ plan and results

struct PlannedRun {
  std::size_t item = 0;
  std::size_t run = 0;  // index into item.runsFor(quick)
  std::string caseFile;
  std::string outputDirectory;
  double work = 1.0;  // steps x (particles + 20), for the ETA
  long long steps = 0;
  std::size_t particles = 0;
};

/// What one run gave for one quantity.
struct Extracted {
  std::optional<double> value;  // single-number operations
  Series curve;                 // the compared (operation: curve) or plotted series
  std::string xLabel, yLabel;   // CSV headers with units
  std::string problem;          // why nothing could be extracted
};

struct Row {
  std::string item, runLabel, quantity, operation;
  std::optional<Comparison> comparison;
  Tolerance tolerance;
  std::string note;  // curve: worst point; failure reason
  bool pass() const { return comparison && comparison->pass; }
};

struct ItemOutcome {
  double wallSeconds = 0.0;
  std::vector<std::string> plots;  // PNG paths
  bool skipped = false;
};

std::string caseLabel(const Item& item, const RunPoint& run) {
  return run.label.empty() ? item.name : fmt::format("{} ({})", item.name, run.label);
}

std::string slug(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '_') out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "quantity" : out;
}

std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e8) return "--:--";
  const long long s = std::llround(seconds);
  return s >= 3600 ? fmt::format("{}:{:02d}:{:02d}", s / 3600, (s % 3600) / 60, s % 60) : fmt::format("{:02d}:{:02d}", s / 60, s % 60);
}

std::string commandOutput(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) out += buffer.data();
  ::pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

// ------------------------------------------------------------------ extraction from the monitor CSV

double singleNumber(Operation op, const Series& s, const Quantity& q, std::string& problem) {
  switch (op) {
    case Operation::Final: return finalValue(s);
    case Operation::Initial: return initialValue(s);
    case Operation::Min: return minimum(s);
    case Operation::Max: return maximum(s);
    case Operation::Mean: return mean(s);
    case Operation::ValueAt: {
      const auto v = interpolate(s, q.at);
      if (!v) problem = fmt::format("{} = {:g} outside the sampled range [{:g}, {:g}]", q.xColumn, q.at, s.x.front(), s.x.back());
      return v.value_or(NAN);
    }
    case Operation::FirstCrossing: {
      const auto v = firstCrossing(s, q.threshold);
      if (!v) problem = fmt::format("'{}' never crosses {:g}", q.column, q.threshold);
      return v.value_or(NAN);
    }
    case Operation::DurationAbove: {
      const auto v = durationAbove(s, q.threshold);
      if (!v) problem = fmt::format("'{}' has no complete interval above {:g}", q.column, q.threshold);
      return v.value_or(NAN);
    }
    default: return NAN;
  }
}

Extracted extract(const Quantity& q, const std::string& runDirectory) {
  Extracted e;
  const std::string file = (fs::path(runDirectory) / (q.monitor + ".csv")).string();
  if (!fs::exists(file)) {
    e.problem = fmt::format("no monitor file {}.csv (is there a monitor named '{}' in the case?)", q.monitor, q.monitor);
    return e;
  }
  const io::CsvTable table = io::readCsv(file);
  const int ix = columnIndex(table.header, q.xColumn), iy = columnIndex(table.header, q.column);
  if (ix < 0 || iy < 0) {
    e.problem = fmt::format("no column '{}' in {}.csv (columns: {})", ix < 0 ? q.xColumn : q.column, q.monitor, fmt::join(table.header, ", "));
    return e;
  }
  e.xLabel = table.header[ix];
  e.yLabel = table.header[iy];
  for (const auto& row : table.rows) {
    if (static_cast<int>(row.size()) <= std::max(ix, iy)) continue;
    e.curve.x.push_back(row[ix]);
    e.curve.y.push_back(row[iy]);
  }
  Series s = q.window ? window(e.curve, q.window->first, q.window->second) : e.curve;
  if (s.x.empty()) {
    e.problem = q.window ? fmt::format("no samples of {}.csv in the window [{:g}, {:g}]", q.monitor, q.window->first, q.window->second)
                         : fmt::format("{}.csv has no rows", q.monitor);
    return e;
  }
  if (q.operation == Operation::Curve) {
    for (double& y : s.y) y = q.scale * y + q.offset;
    e.curve = s;
    return e;
  }
  // Operations act on the column as written; the reported number is scale * result + offset.
  double raw = NAN;
  if (q.operation == Operation::Ratio)
    raw = singleNumber(q.numerator, s, q, e.problem) / singleNumber(q.denominator, s, q, e.problem);
  else
    raw = singleNumber(q.operation, s, q, e.problem);
  e.value = q.scale * raw + q.offset;
  if (!e.problem.empty()) e.value.reset();
  return e;
}

// ------------------------------------------------------------------ plots (JSON specs for tools/plot.py)

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

/// The figure of one quantity of one item: written as JSON next to the runs; returns the PNG path.
std::string writePlotSpec(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs,
                          const std::vector<Extracted>& extracted, const std::vector<Row>& rows, const std::string& itemDirectory,
                          std::vector<std::string>& specs) {
  const std::string png = (fs::path(itemDirectory) / fmt::format("{}_{}.png", item.name, slug(q.name))).string();
  std::vector<PlotSeries> series;
  std::string xLabel = q.plot.xLabel, yLabel = q.plot.yLabel, note;
  const bool sweep = runs.size() > 1 || !item.sweepKey.empty();
  const Extracted* first = nullptr;
  for (const Extracted& e : extracted)
    if (!e.xLabel.empty()) first = first ? first : &e;
  for (const Row& r : rows)
    if (r.comparison)
      note += fmt::format("{}{}: grainflow {:.5g}, reference {:.5g}{}", note.empty() ? "" : "\n",
                          q.across == AcrossRuns::LogLogSlope ? "observed log-log slope" : r.runLabel.empty() ? q.name : r.runLabel,
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
    if (q.across == AcrossRuns::LogLogSlope && computed.x.size() >= 1 && q.reference.value) {
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
  io::writeFileAtomically(specFile, plotSpecJson(png, fmt::format("{}: {}", item.title, q.name), xLabel, yLabel, q.plot, note, series));
  specs.push_back(specFile);
  return png;
}

// ------------------------------------------------------------------ comparison rows

std::vector<Row> compareQuantity(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs,
                                 const std::vector<Extracted>& extracted, const std::vector<std::string>& runFailures) {
  std::vector<Row> rows;
  const std::string opName = operationName(q.operation == Operation::Ratio ? q.operation : q.operation);
  if (q.across == AcrossRuns::LogLogSlope) {
    Row row{item.name, fmt::format("runs over {}", item.sweepKey), q.name, "loglog_slope of " + opName, std::nullopt, q.tolerance, ""};
    std::vector<double> xs, ys;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      if (!extracted[k].value) {
        row.note = fmt::format("{}: {}", caseLabel(item, runs[k]), runFailures[k].empty() ? extracted[k].problem : runFailures[k]);
        rows.push_back(row);
        return rows;
      }
      xs.push_back(runs[k].x);
      ys.push_back(*extracted[k].value);
    }
    if (xs.size() < 2) {
      row.note = "a slope needs at least two runs";
    } else {
      row.comparison = compareValue(logLogSlope(xs, ys), *q.reference.value, q.tolerance);
    }
    rows.push_back(row);
    return rows;
  }
  for (std::size_t k = 0; k < runs.size(); ++k) {
    Row row{item.name, runs[k].label, q.name, opName, std::nullopt, q.tolerance, ""};
    const Extracted& e = extracted[k];
    if (!runFailures[k].empty()) {
      row.note = runFailures[k];
    } else if (!e.problem.empty()) {
      row.note = e.problem;
    } else if (q.operation == Operation::Curve) {
      row.comparison = compareCurve(e.curve, q.reference.data, q.tolerance);
      if (!row.comparison) row.note = "no reference point inside the computed range";
      else {
        std::size_t inside = 0;
        double worstX = NAN;
        for (std::size_t i = 0; i < q.reference.data.x.size(); ++i)
          if (auto v = interpolate(e.curve, q.reference.data.x[i])) {
            ++inside;
            if (q.reference.data.y[i] == row.comparison->reference && *v == row.comparison->computed) worstX = q.reference.data.x[i];
          }
        row.note = fmt::format("worst of {} points, at {} = {:.4g}", inside, q.xColumn, worstX);
      }
    } else {
      std::optional<double> reference = q.reference.value;
      if (!reference) {
        reference = interpolate(q.reference.data, runs[k].x);
        if (!reference) row.note = fmt::format("swept value {:g} outside the reference data", runs[k].x);
      }
      if (reference && e.value) row.comparison = compareValue(*e.value, *reference, q.tolerance);
    }
    rows.push_back(row);
  }
  return rows;
}

std::string formatTolerance(const Tolerance& t) {
  return t.relative ? fmt::format("{:.3g} %", 100.0 * t.value) : fmt::format("{:.3g}", t.value);
}
std::string formatError(const Row& r) {
  if (!r.comparison) return "-";
  return r.tolerance.relative ? fmt::format("{:+.3g} %", 100.0 * r.comparison->error) : fmt::format("{:+.3g}", r.comparison->error);
}

struct TableColumns {
  std::vector<std::string> caseName, quantity, reference, computed, error, tolerance, result;
};

TableColumns tableOf(const std::vector<Row>& rows) {
  TableColumns t;
  for (const Row& r : rows) {
    t.caseName.push_back(r.runLabel.empty() ? r.item : fmt::format("{} ({})", r.item, r.runLabel));
    t.quantity.push_back(r.operation == "curve" ? r.quantity + " [curve]" : r.quantity);
    t.reference.push_back(r.comparison ? fmt::format("{:.6g}", r.comparison->reference) : "-");
    t.computed.push_back(r.comparison ? fmt::format("{:.6g}", r.comparison->computed) : "-");
    t.error.push_back(formatError(r));
    t.tolerance.push_back(formatTolerance(r.tolerance));
    t.result.push_back(r.pass() ? "PASS" : "FAIL");
  }
  return t;
}

std::string textTable(const std::vector<Row>& rows) {
  const TableColumns t = tableOf(rows);
  const std::vector<std::pair<std::string, const std::vector<std::string>*>> cols = {
      {"case", &t.caseName}, {"quantity", &t.quantity}, {"reference", &t.reference}, {"grainflow", &t.computed},
      {"error", &t.error},   {"tolerance", &t.tolerance}, {"result", &t.result}};
  std::vector<std::size_t> width;
  for (const auto& [head, values] : cols) {
    std::size_t w = head.size();
    for (const auto& v : *values) w = std::max(w, v.size());
    width.push_back(w);
  }
  std::string out;
  for (std::size_t c = 0; c < cols.size(); ++c) out += fmt::format("{:<{}}{}", cols[c].first, width[c], c + 1 < cols.size() ? "  " : "\n");
  for (std::size_t c = 0; c < cols.size(); ++c) out += std::string(width[c], '-') + (c + 1 < cols.size() ? "  " : "\n");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < cols.size(); ++c)
      out += fmt::format(fmt::runtime(c >= 2 && c <= 5 ? "{:>{}}{}" : "{:<{}}{}"), (*cols[c].second)[r], width[c], c + 1 < cols.size() ? "  " : "\n");
    if (!rows[r].pass() && !rows[r].note.empty()) out += fmt::format("    ^ {}\n", rows[r].note);
  }
  return out;
}

std::string csvCell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string resultsCsv(const std::vector<Row>& rows) {
  std::string out = "item,run,quantity,operation,reference,grainflow,error,tolerance,tolerance_type,pass,note\n";
  for (const Row& r : rows)
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", csvCell(r.item), csvCell(r.runLabel), csvCell(r.quantity), r.operation,
                       r.comparison ? fmt::format("{:.10g}", r.comparison->reference) : "",
                       r.comparison ? fmt::format("{:.10g}", r.comparison->computed) : "",
                       r.comparison ? fmt::format("{:.6g}", r.comparison->error) : "", fmt::format("{:.6g}", r.tolerance.value),
                       r.tolerance.relative ? "relative" : "absolute", r.pass() ? 1 : 0, csvCell(r.note));
  return out;
}

// ------------------------------------------------------------------ docs/validation.md

std::string markdownTable(const std::vector<Row>& rows) {
  const TableColumns t = tableOf(rows);
  std::string out = "| case | quantity | reference | grainflow | error | tolerance | result |\n|---|---|---:|---:|---:|---:|---|\n";
  for (std::size_t r = 0; r < rows.size(); ++r)
    out += fmt::format("| {} | {} | {} | {} | {} | {} | {}{} |\n", t.caseName[r], t.quantity[r], t.reference[r], t.computed[r], t.error[r],
                       t.tolerance[r], rows[r].pass() ? "pass" : "**FAIL**", rows[r].note.empty() ? "" : " — " + rows[r].note);
  return out;
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model;
  int count = 0;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      ++count;
      if (model.empty()) model = line.substr(line.find(':') + 2);
    }
  }
  return model.empty() ? "unknown" : fmt::format("{} ({} logical CPUs)", model, count);
}

std::string summaryTable(const std::vector<Item>& items, const std::vector<std::vector<Row>>& rowsPerItem,
                         const std::vector<ItemOutcome>& outcomes, const std::string& linkPrefix) {
  std::string out = "| item | what is compared | comparisons | result |\n|---|---|---:|---|\n";
  for (std::size_t i = 0; i < items.size(); ++i) {
    std::size_t passed = 0;
    for (const Row& r : rowsPerItem[i]) passed += r.pass() ? 1 : 0;
    const bool ok = passed == rowsPerItem[i].size();
    out += fmt::format("| [`{}`]({}#{}) | {} | {}/{} | {} |\n", items[i].name, linkPrefix, items[i].name, items[i].title, passed,
                       rowsPerItem[i].size(), ok ? "pass" : "**FAIL**");
  }
  return out;
}

void writeDocs(const std::string& docsDirectory, const std::string& repository, const std::vector<Item>& items,
               const std::vector<std::vector<Row>>& rowsPerItem, const std::vector<ItemOutcome>& outcomes, double wall, int threads) {
  const fs::path docs(docsDirectory), img = docs / "img";
  fs::create_directories(img);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  const std::string commit = commandOutput(fmt::format("git -C {} rev-parse --short=12 HEAD 2>/dev/null", shellQuote(repository)));
  const bool dirty = !commandOutput(fmt::format("git -C {} status --porcelain --untracked-files=no 2>/dev/null", shellQuote(repository))).empty();
  std::string md = "# Validation report\n\n";
  md += "<!-- Generated by `grainflow validate` (full mode, all items). Do not edit: rerun it. -->\n\n";
  md += "Each item is data under `validation/<item>/` (format: [validation-format.md](validation-format.md)): a case file, the "
        "reference (value or CSV with its source), the extraction from the monitor CSVs and the tolerance. Run them with "
        "`grainflow validate` (all items, this report) or `grainflow validate --quick [NAME...]` (reduced, as in ctest).\n\n";
  md += fmt::format("- Date: {}\n- Commit: {}{}\n- Machine: `{}`\n- CPU: {}\n- Threads: {}; total wall time {:.1f} s\n\n", date,
                    commit.empty() ? "unknown" : "`" + commit + "`", dirty ? " (with uncommitted changes)" : "",
                    commandOutput("uname -a"), cpuModel(), threads, wall);
  md += "## Summary\n\n" + summaryTable(items, rowsPerItem, outcomes, "") + "\n";
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& item = items[i];
    md += fmt::format("## `{}`\n\n**{}**", item.name, item.title);
    md += item.description.empty() ? "\n\n" : fmt::format(" — {}\n\n", item.description);
    md += fmt::format("Case: [`validation/{0}/{1}`](../validation/{0}/{1})", item.name, fs::path(item.caseFile).filename().string());
    if (!item.sweepKey.empty()) {
      std::vector<std::string> values;
      for (const RunPoint& r : item.runs) values.push_back(fmt::format("{:g}", r.x));
      md += fmt::format("; sweep `{}` = {}", item.sweepKey, fmt::join(values, ", "));
    }
    md += fmt::format("; wall time {:.1f} s.\n\n", outcomes[i].wallSeconds);
    for (const Quantity& q : item.quantities)
      md += fmt::format("- `{}`: {} of `{}` in `{}.csv`{}; reference: {}\n", q.name, operationName(q.operation), q.column, q.monitor,
                        q.across == AcrossRuns::LogLogSlope ? ", observed order (log-log slope over the runs)" : "", q.reference.source);
    md += "\n" + markdownTable(rowsPerItem[i]) + "\n";
    for (const std::string& png : outcomes[i].plots) {
      std::error_code ec;
      const fs::path target = img / fs::path(png).filename();
      if (!fs::exists(png)) continue;
      fs::copy_file(png, target, fs::copy_options::overwrite_existing, ec);
      if (!ec) md += fmt::format("![{}](img/{})\n\n", item.name, target.filename().string());
    }
  }
  io::writeFileAtomically((docs / "validation.md").string(), md);
  std::printf("wrote %s\n", (docs / "validation.md").c_str());

  // README: the summary between markers, if the README has them.
  const fs::path readme = fs::path(repository) / "README.md";
  const std::string begin = "<!-- validation-summary:begin -->", end = "<!-- validation-summary:end -->";
  if (fs::exists(readme)) {
    std::string text = io::readFile(readme.string());
    const auto b = text.find(begin), e = text.find(end);
    if (b != std::string::npos && e != std::string::npos && b < e) {
      text = text.substr(0, b + begin.size()) + "\n" + summaryTable(items, rowsPerItem, outcomes, "docs/validation.md") + text.substr(e);
      io::writeFileAtomically(readme.string(), text);
      std::printf("updated the validation summary in %s\n", readme.c_str());
    }
  }
}

std::string defaultValidationDirectory() {
  if (fs::exists("validation")) return "validation";
  return (fs::path(GRAINFLOW_SOURCE_DIR) / "validation").string();
}

}  // namespace

int runValidate(const ValidateOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::string validationDirectory = options.validationDirectory.empty() ? defaultValidationDirectory() : options.validationDirectory;
  const fs::path repository = fs::absolute(validationDirectory).lexically_normal().parent_path();
  const std::vector<std::string> available = listItems(validationDirectory);
  std::vector<std::string> selected = options.names.empty() ? available : options.names;
  for (const std::string& name : selected)
    if (std::find(available.begin(), available.end(), name) == available.end()) {
      std::fprintf(stderr, "grainflow: no validation item '%s' in %s (available: %s)\n", name.c_str(), validationDirectory.c_str(),
                   fmt::format("{}", fmt::join(available, ", ")).c_str());
      return kExitUsage;
    }
  if (selected.empty()) {
    std::fprintf(stderr, "grainflow: no validation items in %s\n", validationDirectory.c_str());
    return kExitUsage;
  }
  setThreadCount(options.threads);

  // Load every item and build (hence check) every case before running anything.
  std::vector<Item> items;
  for (const std::string& name : selected) items.push_back(loadItem((fs::path(validationDirectory) / name).string()));
  std::vector<PlannedRun> plan;
  std::vector<ItemOutcome> outcomes(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& item = items[i];
    if (options.quick && item.skipQuick) {
      outcomes[i].skipped = true;
      continue;
    }
    const std::string caseText = io::readFile(item.caseFile);
    const auto& runs = item.runsFor(options.quick);
    for (std::size_t k = 0; k < runs.size(); ++k) {
      PlannedRun p;
      p.item = i;
      p.run = k;
      p.outputDirectory = (fs::path(options.outputDirectory) / item.name / (runs.size() == 1 ? "run" : fmt::format("run_{}", k))).string();
      fs::create_directories(p.outputDirectory);
      std::vector<Override> overrides = options.quick ? item.quickOverrides : std::vector<Override>{};
      overrides.insert(overrides.end(), runs[k].overrides.begin(), runs[k].overrides.end());
      p.caseFile = (fs::path(p.outputDirectory) / "case.yaml").string();
      io::writeFileAtomically(p.caseFile, fmt::format("# {} with {} override(s) applied by grainflow validate{}\n{}", item.caseFile,
                                                      overrides.size(), options.quick ? " --quick" : "",
                                                      applyOverrides(caseText, overrides, item.caseFile)));
      RunOptions runOptions;
      runOptions.threads = options.threads;
      runOptions.outputDirectory = p.outputDirectory;
      runOptions.overwrite = true;
      runOptions.quiet = true;
      try {
        auto simulation = Simulation::fromFile(p.caseFile, runOptions);
        p.steps = std::llround(simulation->settings().endTime / simulation->settings().demStep);
        p.particles = simulation->dem().particles().size();
        p.work = static_cast<double>(p.steps) * (static_cast<double>(p.particles) + 20.0);  // + fixed cost per step
      } catch (const CaseError&) {
        std::fprintf(stderr, "grainflow: validation item '%s' (%s%s) has an invalid case:\n", item.name.c_str(), item.caseFile.c_str(),
                     overrides.empty() ? "" : " with the overrides of validation.yaml");
        throw;
      }
      plan.push_back(p);
    }
  }

  double totalWork = 0.0, doneWork = 0.0, runWall = 0.0;
  for (const PlannedRun& p : plan) totalWork += p.work;
  std::printf("grainflow validate%s: %zu item(s), %zu run(s), %d thread(s), output in %s\n", options.quick ? " --quick" : "", items.size(),
              plan.size(), threadCount(), options.outputDirectory.c_str());

  // Run, then extract every quantity of every run.
  std::vector<std::vector<std::vector<Extracted>>> extracted(items.size());  // [item][quantity][run]
  std::vector<std::vector<std::string>> failures(items.size());              // [item][run]
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::size_t runs = items[i].runsFor(options.quick).size();
    extracted[i].assign(items[i].quantities.size(), std::vector<Extracted>(runs));
    failures[i].assign(runs, "");
  }
  for (std::size_t n = 0; n < plan.size(); ++n) {
    const PlannedRun& p = plan[n];
    const Item& item = items[p.item];
    const RunPoint& point = item.runsFor(options.quick)[p.run];
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double eta = doneWork > 0.0 ? runWall / doneWork * (totalWork - doneWork) : NAN;
    std::printf("[%zu/%zu, %s elapsed, ETA %s] %s: %lld steps, %zu particle(s) ... ", n + 1, plan.size(), formatDuration(elapsed).c_str(),
                formatDuration(eta).c_str(), caseLabel(item, point).c_str(), p.steps, p.particles);
    std::fflush(stdout);
    const auto runStart = std::chrono::steady_clock::now();
    RunOptions runOptions;
    runOptions.threads = options.threads;
    runOptions.outputDirectory = p.outputDirectory;
    runOptions.overwrite = true;
    runOptions.quiet = true;
    try {
      auto simulation = Simulation::fromFile(p.caseFile, runOptions);
      simulation->prepare();
      if (simulation->run() == RunStatus::Interrupted) {
        std::printf("interrupted\n");
        return kExitInterrupted;
      }
    } catch (const DivergenceError& e) {
      failures[p.item][p.run] = e.what();
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count();
    runWall += seconds;
    doneWork += p.work;
    outcomes[p.item].wallSeconds += seconds;
    std::printf("%s in %.2f s\n", failures[p.item][p.run].empty() ? "done" : "DIVERGED", seconds);
    std::fflush(stdout);
    if (failures[p.item][p.run].empty())
      for (std::size_t q = 0; q < item.quantities.size(); ++q)
        extracted[p.item][q][p.run] = extract(item.quantities[q], p.outputDirectory);
  }

  // Compare, print, write results and plots.
  std::vector<Row> allRows;
  std::vector<std::vector<Row>> rowsPerItem(items.size());
  std::vector<std::string> specs;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (outcomes[i].skipped) continue;
    const auto& runs = items[i].runsFor(options.quick);
    const std::string itemDirectory = (fs::path(options.outputDirectory) / items[i].name).string();
    for (std::size_t q = 0; q < items[i].quantities.size(); ++q) {
      const auto rows = compareQuantity(items[i], items[i].quantities[q], runs, extracted[i][q], failures[i]);
      rowsPerItem[i].insert(rowsPerItem[i].end(), rows.begin(), rows.end());
      if (options.plots)
        outcomes[i].plots.push_back(writePlotSpec(items[i], items[i].quantities[q], runs, extracted[i][q], rows, itemDirectory, specs));
    }
    allRows.insert(allRows.end(), rowsPerItem[i].begin(), rowsPerItem[i].end());
  }
  std::size_t passed = 0;
  for (const Row& r : allRows) passed += r.pass() ? 1 : 0;
  std::printf("\n%s\n", textTable(allRows).c_str());
  for (std::size_t i = 0; i < items.size(); ++i)
    if (outcomes[i].skipped) std::printf("skipped in --quick mode: %s\n", items[i].name.c_str());
  const std::string resultsFile = (fs::path(options.outputDirectory) / "results.csv").string();
  io::writeFileAtomically(resultsFile, resultsCsv(allRows));
  std::printf("results: %s\n", resultsFile.c_str());

  if (options.plots && !specs.empty()) {
    const PlotTool tool = findPlotTool(repository.string());
    if (!tool.available()) {
      std::printf("plots skipped: %s; %s\n", tool.problem.c_str(), kPlotInstallHint);
      for (auto& o : outcomes) o.plots.clear();
    } else {
      std::vector<std::string> arguments = {"validation"};
      arguments.insert(arguments.end(), specs.begin(), specs.end());
      if (runPlotScript(tool, arguments) != 0) std::printf("plots: %s failed (numbers above are unaffected)\n", tool.script.c_str());
      else std::printf("plots: %zu PNG(s) in %s/<item>/\n", specs.size(), options.outputDirectory.c_str());
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.quick && options.names.empty() && options.writeDocs)
    writeDocs(options.docsDirectory.empty() ? (repository / "docs").string() : options.docsDirectory, repository.string(), items,
              rowsPerItem, outcomes, wall, threadCount());
  std::printf("%zu of %zu comparison(s) passed, %zu failed; wall time %.1f s\n", passed, allRows.size(), allRows.size() - passed, wall);
  return passed == allRows.size() ? kExitOk : kExitValidationFailed;
}

}  // namespace gf::app
