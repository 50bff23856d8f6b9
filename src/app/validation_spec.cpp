#include "app/validation_spec.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "core/params.hpp"
#include "io/atomic_file.hpp"

namespace gf::app::validation {

namespace fs = std::filesystem;

const std::vector<std::pair<std::string, Operation>>& operationNames() {
  static const std::vector<std::pair<std::string, Operation>> names = {
      {"final", Operation::Final},           {"initial", Operation::Initial},
      {"min", Operation::Min},               {"max", Operation::Max},
      {"mean", Operation::Mean},             {"value_at", Operation::ValueAt},
      {"first_crossing", Operation::FirstCrossing}, {"duration_above", Operation::DurationAbove},
      {"ratio", Operation::Ratio},           {"curve", Operation::Curve},
      {"profile", Operation::Profile}};
  return names;
}

std::string operationName(Operation op) {
  for (const auto& [name, value] : operationNames())
    if (value == op) return name;
  return "?";
}

const std::vector<std::pair<std::string, AcrossRuns>>& acrossRunsNames() {
  static const std::vector<std::pair<std::string, AcrossRuns>> names = {{"none", AcrossRuns::None},
                                                                         {"loglog_slope", AcrossRuns::LogLogSlope},
                                                                         {"richardson_order", AcrossRuns::RichardsonOrder},
                                                                         {"min_increment", AcrossRuns::MinIncrement},
                                                                         {"gap_closed", AcrossRuns::GapClosed}};
  return names;
}

std::string acrossRunsName(AcrossRuns a) {
  for (const auto& [name, value] : acrossRunsNames())
    if (value == a) return name;
  return "?";
}

int columnIndex(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    std::string h = header[i];
    const auto bracket = h.find(" [");
    if (bracket != std::string::npos) h = h.substr(0, bracket);
    if (h == name) return static_cast<int>(i);
  }
  return -1;
}

std::string columnUnit(const std::string& headerEntry) {
  const auto open = headerEntry.find(" [");
  const auto close = headerEntry.rfind(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return "";
  return headerEntry.substr(open + 2, close - open - 2);
}

namespace {

/// A YAML map of validation.yaml with its key path, for strict reading and file:line errors.
class Map {
 public:
  Map(YAML::Node node, std::string file, std::string path) : node_(node), file_(std::move(file)), path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& found, const std::string& expected) const {
    const YAML::Node at = node_[key];
    const YAML::Mark mark = at ? at.Mark() : node_.Mark();
    throw CaseError(FileLocation{file_, mark.line + 1, mark.column + 1}, keyPath(key), found, expected);
  }
  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) const { return node_[key].IsDefined() && !node_[key].IsNull(); }
  YAML::Node raw(const std::string& key) const { return node_[key]; }

  void allowOnly(const std::vector<std::string>& keys) const {
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
      const std::string near = closestMatch(key, keys);
      const YAML::Mark mark = entry.first.Mark();
      throw CaseError(FileLocation{file_, mark.line + 1, mark.column + 1}, keyPath(key), "an unknown key",
                      near.empty() ? fmt::format("one of: {}", fmt::join(keys, ", ")) : fmt::format("'{}'", near));
    }
  }

  std::string text(const std::string& key, const std::optional<std::string>& fallback = std::nullopt) const {
    if (!has(key)) {
      if (fallback) return *fallback;
      fail(key, "nothing", "a value (required)");
    }
    if (!node_[key].IsScalar()) fail(key, "a list or map", "a text");
    return node_[key].as<std::string>();
  }
  double real(const std::string& key, const std::optional<double>& fallback = std::nullopt) const {
    if (!has(key)) {
      if (fallback) return *fallback;
      fail(key, "nothing", "a number (required)");
    }
    return toReal(node_[key], key);
  }
  bool boolean(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    bool value = false;
    if (!node_[key].IsScalar() || !YAML::convert<bool>::decode(node_[key], value))
      fail(key, "'" + node_[key].Scalar() + "'", "true or false");
    return value;
  }
  std::vector<double> reals(const std::string& key) const {
    const YAML::Node list = node_[key];
    if (!list.IsSequence() || list.size() == 0) fail(key, "no list", "a non-empty list of numbers");
    std::vector<double> out;
    for (const YAML::Node& v : list) out.push_back(toReal(v, key));
    return out;
  }
  Map map(const std::string& key) const {
    if (!node_[key].IsMap()) fail(key, has(key) ? "not a map" : "nothing", "a map of keys");
    return Map(node_[key], file_, keyPath(key));
  }
  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const std::string& fallback) const {
    std::string value = text(key, fallback);  // not const: returned by move
    if (std::find(allowed.begin(), allowed.end(), value) == allowed.end())
      fail(key, "'" + value + "'", fmt::format("one of: {}", fmt::join(allowed, ", ")));
    return value;
  }
  const std::string& file() const { return file_; }

 private:
  double toReal(const YAML::Node& v, const std::string& key) const {
    double value = 0.0;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, value)) fail(key, "'" + YAML::Dump(v) + "'", "a number");
    return value;
  }
  YAML::Node node_;
  std::string file_;
  std::string path_;
};

std::string dumpYaml(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetSeqFormat(YAML::Flow);
  out.SetMapFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

std::vector<Override> readOverrides(const Map& parent, const std::string& key) {
  std::vector<Override> out;
  if (!parent.has(key)) return out;
  const YAML::Node map = parent.raw(key);
  if (!map.IsMap()) parent.fail(key, "not a map", "a map 'key.path: value'");
  for (const auto& entry : map) out.push_back({entry.first.as<std::string>(), dumpYaml(entry.second)});
  return out;
}

Operation readOperation(const Map& m, const std::string& key, const std::string& fallback) {
  std::vector<std::string> names;
  for (const auto& [name, op] : operationNames()) names.push_back(name);
  const std::string name = m.choice(key, names, fallback);
  for (const auto& [n, op] : operationNames())
    if (n == name) return op;
  return Operation::Final;
}

/// Reference CSV: '#' lines are comments (provenance), the first other line is the header.
Series readReferenceCsv(const Map& ref, const std::string& path, const std::string& xColumn, const std::string& yColumn) {
  std::istringstream lines(io::readFile(path));
  std::vector<std::string> header;
  Series data;
  int ix = -1, iy = -1;
  std::string line;
  int lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      ix = columnIndex(header, xColumn);
      iy = columnIndex(header, yColumn);
      if (ix < 0) ref.fail("x", fmt::format("no column '{}' in {} (columns: {})", xColumn, path, fmt::join(header, ", ")), "a column of the reference CSV");
      if (iy < 0) ref.fail("y", fmt::format("no column '{}' in {} (columns: {})", yColumn, path, fmt::join(header, ", ")), "a column of the reference CSV");
      continue;
    }
    try {
      data.x.push_back(std::stod(cells.at(ix)));
      data.y.push_back(std::stod(cells.at(iy)));
    } catch (const std::exception&) {
      throw CaseError(FileLocation{path, lineNumber, 0}, ref.keyPath("file"), "'" + line + "'", "a row of numbers");
    }
  }
  if (data.x.empty()) ref.fail("file", path + " without data rows", "a CSV with a header and at least one row");
  for (std::size_t i = 1; i < data.x.size(); ++i)
    if (data.x[i] < data.x[i - 1]) ref.fail("x", "column '" + xColumn + "' not sorted", "non-decreasing x values");
  return data;
}

/// reference.points: [[x, y], ...] in any order, returned sorted by x.
Series readReferencePoints(const Map& ref) {
  const YAML::Node list = ref.raw("points");
  if (!list.IsSequence() || list.size() == 0) ref.fail("points", "no list", "a non-empty list of [x, y] pairs");
  std::vector<std::pair<double, double>> points;
  for (const YAML::Node& pair : list) {
    double x = 0.0, y = 0.0;
    if (!pair.IsSequence() || pair.size() != 2 || !YAML::convert<double>::decode(pair[0], x) ||
        !YAML::convert<double>::decode(pair[1], y))
      ref.fail("points", "'" + dumpYaml(pair) + "'", "[x, y] pairs of numbers");
    points.emplace_back(x, y);
  }
  return sortedByX(std::move(points));
}

PlotSpec readPlot(const Map& q);
Tolerance readTolerance(const Map& q, const std::string& key, const Quantity& quantity);

Quantity readQuantity(const Map& q, const std::string& directory, bool hasSweep) {
  q.allowOnly({"name", "monitor", "column", "x_column", "operation", "numerator", "denominator", "window", "threshold",
               "at", "scale", "offset", "across_runs", "reference", "tolerance", "quick_tolerance", "plot"});
  Quantity out;
  out.name = q.text("name");
  out.monitor = q.text("monitor");
  out.column = q.text("column");
  out.xColumn = q.text("x_column", std::string("time"));
  out.operation = readOperation(q, "operation", "final");
  if (out.operation == Operation::Ratio) {
    out.numerator = readOperation(q, "numerator", "final");
    out.denominator = readOperation(q, "denominator", "initial");
    for (Operation op : {out.numerator, out.denominator})
      if (op == Operation::Ratio || op == Operation::Curve || op == Operation::Profile)
        q.fail("numerator", "'" + operationName(op) + "'", "a single-number operation (final, max, ...)");
  } else if (q.has("numerator") || q.has("denominator")) {
    q.fail(q.has("numerator") ? "numerator" : "denominator", "a ratio part", "operation: ratio");
  }
  if (q.has("window")) {
    const auto w = q.reals("window");
    if (w.size() != 2 || !(w[0] <= w[1])) q.fail("window", "not [from, to]", "[from, to] with from <= to");
    out.window = std::make_pair(w[0], w[1]);
  }
  out.threshold = q.real("threshold", 0.0);
  if (out.operation == Operation::ValueAt) out.at = q.real("at");
  out.scale = q.real("scale", 1.0);
  out.offset = q.real("offset", 0.0);
  std::vector<std::string> acrossNames;
  for (const auto& [name, kind] : acrossRunsNames()) acrossNames.push_back(name);
  const std::string across = q.choice("across_runs", acrossNames, "none");
  for (const auto& [name, kind] : acrossRunsNames())
    if (name == across) out.across = kind;
  if (out.across != AcrossRuns::None && !hasSweep) q.fail("across_runs", "'" + across + "' without a sweep", "a sweep (at least two runs)");
  const bool curveLike = out.operation == Operation::Curve || out.operation == Operation::Profile;
  if (out.across != AcrossRuns::None && curveLike)
    q.fail("across_runs", "'" + across + "' with operation: " + operationName(out.operation), "a single-number operation");
  if (out.operation == Operation::Profile && !q.has("x_column"))
    q.fail("operation", "profile without x_column", "x_column: the position column of the profile (e.g. y of a line along y)");

  const Map ref = q.map("reference");
  ref.allowOnly({"value", "file", "x", "y", "points", "source"});
  out.reference.source = ref.text("source");
  if (int(ref.has("value")) + int(ref.has("file")) + int(ref.has("points")) != 1)
    ref.fail("value", "none or several of 'value', 'file' and 'points'", "exactly one of them");
  if (ref.has("value")) {
    out.reference.value = ref.real("value");
    if (curveLike)
      ref.fail("value", "a single value for operation: " + operationName(out.operation), "points: [[x, y], ...] or file: with the reference points");
  } else if (ref.has("points")) {
    out.reference.data = readReferencePoints(ref);
    if (!curveLike && !hasSweep)
      ref.fail("points", "reference points for a single number without a sweep", "value: (or a sweep, or operation: curve or profile)");
    if (out.across != AcrossRuns::None) ref.fail("points", "reference points for across_runs", "value: (the expected order)");
  } else {
    out.reference.file = (fs::path(directory) / ref.text("file")).string();
    out.reference.xColumn = ref.text("x");
    out.reference.yColumn = ref.text("y");
    if (!fs::exists(out.reference.file)) ref.fail("file", "'" + out.reference.file + "' (missing)", "an existing CSV file");
    out.reference.data = readReferenceCsv(ref, out.reference.file, out.reference.xColumn, out.reference.yColumn);
    if (!curveLike && !hasSweep)
      ref.fail("file", "a reference curve for a single number without a sweep", "value: (or a sweep, or operation: curve or profile)");
    if (out.across != AcrossRuns::None) ref.fail("file", "a reference curve for across_runs", "value: (the expected order)");
  }

  out.plot = readPlot(q);
  out.tolerance = readTolerance(q, "tolerance", out);
  if (q.has("quick_tolerance")) out.quickTolerance = readTolerance(q, "quick_tolerance", out);
  return out;
}

Tolerance readTolerance(const Map& q, const std::string& key, const Quantity& quantity) {
  const Map tol = q.map(key);
  tol.allowOnly({"absolute", "relative", "lower_bound"});
  Tolerance out;
  out.lowerBound = tol.boolean("lower_bound", false);
  if (out.lowerBound) {
    if (tol.has("absolute") || tol.has("relative"))
      tol.fail(tol.has("absolute") ? "absolute" : "relative", "a tolerance with lower_bound: true", "lower_bound alone");
    if (!quantity.reference.value) tol.fail("lower_bound", "a lower bound without reference.value", "reference: {value: BOUND}");
    return out;
  }
  if (tol.has("absolute") == tol.has("relative")) tol.fail("absolute", "both or neither of 'absolute' and 'relative' (or lower_bound: true)", "exactly one of them");
  out.relative = tol.has("relative");
  out.value = tol.real(out.relative ? "relative" : "absolute");
  if (!(out.value >= 0.0)) tol.fail(out.relative ? "relative" : "absolute", "a negative number", ">= 0");
  return out;
}

PlotSpec readPlot(const Map& q) {
  PlotSpec out;
  if (q.has("plot")) {
    const Map plot = q.map("plot");
    plot.allowOnly({"x_label", "y_label", "log_x", "log_y", "reference_style", "reference_label", "figure", "swap_axes"});
    out.referenceLabel = plot.text("reference_label", std::string("reference"));
    out.referenceStyle = plot.choice("reference_style", {"auto", "points", "line"}, "auto");
    out.figure = plot.text("figure", std::string());
    out.swapAxes = plot.boolean("swap_axes", false);
    out.xLabel = plot.text("x_label", std::string());
    out.yLabel = plot.text("y_label", std::string());
    out.logX = plot.boolean("log_x", false);
    out.logY = plot.boolean("log_y", false);
  }
  return out;
}

std::vector<RunPoint> readSweepRuns(const Map& sweep, const std::string& valuesKey, const std::string& key,
                                    const std::vector<std::pair<std::string, std::vector<std::string>>>& with) {
  std::vector<RunPoint> runs;
  const YAML::Node values = sweep.raw(valuesKey);
  if (!values.IsSequence() || values.size() == 0) sweep.fail(valuesKey, "no list", "a non-empty list of numbers");
  for (std::size_t i = 0; i < values.size(); ++i) {
    RunPoint run;
    double x = 0.0;
    if (!values[i].IsScalar() || !YAML::convert<double>::decode(values[i], x))
      sweep.fail(valuesKey, "'" + dumpYaml(values[i]) + "'", "numbers (the x values of the sweep plot)");
    run.x = x;
    run.label = fmt::format("{} = {}", key, values[i].Scalar());
    run.overrides.push_back({key, values[i].Scalar()});
    runs.push_back(std::move(run));
  }
  // 'with': other keys set together with the swept one, one value per swept value (full values only).
  if (valuesKey == "values")
    for (const auto& [path, list] : with) {
      if (list.size() != runs.size())
        sweep.fail("with", fmt::format("{} values for '{}'", list.size(), path), fmt::format("{} (one per swept value)", runs.size()));
      for (std::size_t i = 0; i < runs.size(); ++i) runs[i].overrides.push_back({path, list[i]});
    }
  return runs;
}

}  // namespace

std::vector<std::string> listItems(const std::string& validationDirectory) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(validationDirectory, ec))
    if (entry.is_directory() && fs::exists(entry.path() / "validation.yaml")) names.push_back(entry.path().filename().string());
  if (ec) throw Error(fmt::format("cannot read the validation directory '{}': {}", validationDirectory, ec.message()));
  std::sort(names.begin(), names.end());
  return names;
}

Item loadItem(const std::string& directory) {
  const std::string file = (fs::path(directory) / "validation.yaml").string();
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw CaseError(FileLocation{file, 0, 0}, "", "no readable file", "validation/<name>/validation.yaml");
  } catch (const YAML::Exception& e) {
    throw CaseError(FileLocation{file, e.mark.line + 1, e.mark.column + 1}, "", "invalid YAML: " + e.msg, "valid YAML");
  }
  if (!root.IsMap()) throw CaseError(FileLocation{file, 1, 1}, "", "not a map", "a map of keys (title, case, quantities, ...)");
  const Map m(root, file, "");
  m.allowOnly({"title", "description", "case", "quick", "skip_quick", "report_quick", "sweep", "quantities"});
  Item item;
  item.directory = directory;
  item.name = fs::path(directory).filename().string();
  if (item.name.empty()) item.name = fs::path(directory).parent_path().filename().string();
  item.title = m.text("title");
  item.description = m.text("description", std::string());
  item.caseFile = (fs::path(directory) / m.text("case", std::string("case.yaml"))).string();
  if (!fs::exists(item.caseFile)) m.fail("case", "'" + item.caseFile + "' (missing)", "an existing case file");
  item.quickOverrides = readOverrides(m, "quick");
  item.skipQuick = m.boolean("skip_quick", false);
  item.reportQuick = m.boolean("report_quick", false);
  if (item.reportQuick && item.skipQuick)
    m.fail("report_quick", "true together with skip_quick: true", "report_quick only for an item that has a --quick run");

  const bool hasSweep = m.has("sweep");
  if (hasSweep) {
    const Map sweep = m.map("sweep");
    sweep.allowOnly({"key", "values", "quick_values", "label", "with"});
    item.sweepKey = sweep.text("key");
    item.sweepLabel = sweep.text("label", item.sweepKey);
    std::vector<std::pair<std::string, std::vector<std::string>>> with;
    if (sweep.has("with")) {
      const YAML::Node w = sweep.raw("with");
      if (!w.IsMap()) sweep.fail("with", "not a map", "a map 'key.path: [one value per swept value]'");
      for (const auto& entry : w) {
        if (!entry.second.IsSequence()) sweep.fail("with", "'" + entry.first.as<std::string>() + "' without a list", "a list per key");
        std::vector<std::string> values;
        for (const YAML::Node& v : entry.second) values.push_back(dumpYaml(v));
        with.emplace_back(entry.first.as<std::string>(), values);
      }
    }
    item.runs = readSweepRuns(sweep, "values", item.sweepKey, with);
    if (sweep.has("quick_values")) {
      if (!with.empty()) {
        // Quick values must be a subset of the full values so that the 'with' keys follow them.
        for (const YAML::Node& v : sweep.raw("quick_values")) {
          const auto match = std::find_if(item.runs.begin(), item.runs.end(),
                                          [&](const RunPoint& r) { return r.label == item.sweepKey + " = " + v.Scalar(); });
          if (match == item.runs.end()) sweep.fail("quick_values", "'" + v.Scalar() + "'", "values out of 'values' (because of 'with')");
          item.quickRuns.push_back(*match);
        }
      } else {
        item.quickRuns = readSweepRuns(sweep, "quick_values", item.sweepKey, with);
      }
    } else {
      item.quickRuns = item.runs;
    }
  } else {
    item.runs = item.quickRuns = {RunPoint{}};
  }

  if (!m.has("quantities") || !m.raw("quantities").IsSequence() || m.raw("quantities").size() == 0)
    m.fail("quantities", "no list", "a list of compared quantities");
  const YAML::Node quantities = m.raw("quantities");
  for (std::size_t i = 0; i < quantities.size(); ++i) {
    if (!quantities[i].IsMap()) m.fail("quantities", "an entry that is not a map", "maps (name, monitor, column, ...)");
    item.quantities.push_back(readQuantity(Map(quantities[i], file, fmt::format("quantities[{}]", i)), directory, hasSweep));
    for (std::size_t j = 0; j < i; ++j)
      if (item.quantities[j].name == item.quantities[i].name)
        Map(quantities[i], file, fmt::format("quantities[{}]", i)).fail("name", "'" + item.quantities[i].name + "' twice", "unique names");
  }
  for (std::size_t i = 0; i < item.quantities.size(); ++i) {
    const Quantity& q = item.quantities[i];
    const std::size_t needed = q.across == AcrossRuns::RichardsonOrder || q.across == AcrossRuns::GapClosed ? 3
                                : q.across == AcrossRuns::None                                              ? 0
                                                                                                            : 2;
    for (const auto* runs : {&item.runs, &item.quickRuns}) {
      const std::string which = runs == &item.runs ? "sweep.values" : "sweep.quick_values";
      if (runs->size() < needed)
        Map(quantities[i], file, fmt::format("quantities[{}]", i))
            .fail("across_runs", fmt::format("{} with {} run(s) in {}", acrossRunsName(q.across), runs->size(), which),
                  fmt::format("at least {} runs", needed));
      if (q.across != AcrossRuns::RichardsonOrder) continue;
      const std::size_t n = runs->size();
      const double r1 = (*runs)[n - 2].x / (*runs)[n - 3].x, r2 = (*runs)[n - 1].x / (*runs)[n - 2].x;
      if (!(r1 > 0.0) || r1 == 1.0 || std::abs(r2 / r1 - 1.0) > 1e-6)
        Map(quantities[i], file, fmt::format("quantities[{}]", i))
            .fail("across_runs", fmt::format("richardson_order with ratios {:g} and {:g} between the last three values of {}", r1, r2, which),
                  "a constant refinement ratio (e.g. 16, 32, 64)");
    }
  }
  return item;
}

namespace {
struct PathStep {
  std::string key;
  long long index = -1;  // >= 0: list index after the key
};

std::vector<PathStep> parsePath(const std::string& path) {
  std::vector<PathStep> steps;
  std::istringstream parts(path);
  for (std::string part; std::getline(parts, part, '.');) {
    const auto bracket = part.find('[');
    if (bracket == std::string::npos) {
      steps.push_back({part, -1});
      continue;
    }
    steps.push_back({part.substr(0, bracket), -1});
    std::size_t pos = bracket;
    while (pos < part.size() && part[pos] == '[') {
      const auto close = part.find(']', pos);
      if (close == std::string::npos) throw std::invalid_argument("unclosed [");
      steps.push_back({"", std::stoll(part.substr(pos + 1, close - pos - 1))});
      pos = close + 1;
    }
    if (pos != part.size()) throw std::invalid_argument("text after ]");
  }
  return steps;
}
}  // namespace

std::string applyOverrides(const std::string& caseText, const std::vector<Override>& overrides, const std::string& origin) {
  YAML::Node root = YAML::Load(caseText);
  for (const Override& o : overrides) {
    std::vector<PathStep> steps;
    try {
      steps = parsePath(o.path);
    } catch (const std::exception&) {
      throw CaseError(FileLocation{origin, 0, 0}, o.path, "a malformed key path", "a path like 'time.end' or 'materials[0].restitution'");
    }
    YAML::Node node = root;
    for (std::size_t s = 0; s < steps.size(); ++s) {
      const PathStep& step = steps[s];
      const bool last = s + 1 == steps.size();
      YAML::Node value = YAML::Load(o.yaml);
      if (step.index >= 0) {
        if (!node.IsSequence() || step.index >= static_cast<long long>(node.size()))
          throw CaseError(FileLocation{origin, 0, 0}, o.path,
                          fmt::format("no entry [{}] in the case (the list has {} entries)", step.index, node.IsSequence() ? node.size() : 0),
                          "an index into an existing list");
        if (last) {
          node[static_cast<std::size_t>(step.index)] = value;
        } else {
          YAML::Node child = node[static_cast<std::size_t>(step.index)];
          node.reset(child);
        }
      } else {
        if (node.IsDefined() && !node.IsMap() && !node.IsNull())
          throw CaseError(FileLocation{origin, 0, 0}, o.path, fmt::format("'{}' below a value that is not a map", step.key), "a path through maps");
        if (last) {
          node[step.key] = value;
        } else {
          YAML::Node child = node[step.key];
          node.reset(child);
        }
      }
    }
  }
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

}  // namespace gf::app::validation
