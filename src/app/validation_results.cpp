#include "app/validation_results.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "io/csv_series.hpp"

namespace gf::app::validation {

namespace fs = std::filesystem;

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

namespace {

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

}  // namespace

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
  if (q.operation == Operation::Profile) {
    // Long-format CSV (fluid_line_profile): the rows of the last sample time.
    const int it = columnIndex(table.header, "time");
    if (it < 0 || table.rows.empty()) {
      e.problem = it < 0 ? fmt::format("no column 'time' in {}.csv", q.monitor) : fmt::format("{}.csv has no rows", q.monitor);
      return e;
    }
    std::vector<double> time, position, value;
    for (const auto& row : table.rows) {
      if (static_cast<int>(row.size()) <= std::max({it, ix, iy})) continue;
      time.push_back(row[it]);
      position.push_back(row[ix]);
      value.push_back(row[iy]);
    }
    e.curve = lastProfile(time, position, value);
    e.profileTime = time.back();
  } else {
    for (const auto& row : table.rows) {
      if (static_cast<int>(row.size()) <= std::max(ix, iy)) continue;
      e.curve.x.push_back(row[ix]);
      e.curve.y.push_back(row[iy]);
    }
  }
  Series s = q.window ? window(e.curve, q.window->first, q.window->second) : e.curve;
  if (s.x.empty()) {
    e.problem = q.window ? fmt::format("no samples of {}.csv in the window [{:g}, {:g}]", q.monitor, q.window->first, q.window->second)
                         : fmt::format("{}.csv has no rows", q.monitor);
    return e;
  }
  if (q.operation == Operation::Curve || q.operation == Operation::Profile) {
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

std::vector<Row> compareQuantity(const Item& item, const Quantity& q, const std::vector<RunPoint>& runs,
                                 const std::vector<Extracted>& extracted, const std::vector<std::string>& runFailures) {
  std::vector<Row> rows;
  const std::string opName = operationName(q.operation);
  if (q.across != AcrossRuns::None) {
    Row row{item.name, fmt::format("runs over {}", item.sweepKey), q.name, acrossRunsName(q.across) + " of " + opName, std::nullopt, q.tolerance, "", std::nullopt};
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
    try {
      const double computed = q.across == AcrossRuns::LogLogSlope       ? logLogSlope(xs, ys)
                              : q.across == AcrossRuns::RichardsonOrder ? richardsonOrder(xs, ys)
                              : q.across == AcrossRuns::GapClosed       ? gapClosed(xs, ys)
                                                                        : minIncrement(xs, ys);
      row.comparison = compareValue(computed, *q.reference.value, q.tolerance);
    } catch (const std::invalid_argument& e) {
      row.note = e.what();
    }
    rows.push_back(row);
    return rows;
  }
  for (std::size_t k = 0; k < runs.size(); ++k) {
    Row row{item.name, runs[k].label, q.name, opName, std::nullopt, q.tolerance, "", std::nullopt};
    const Extracted& e = extracted[k];
    if (q.operation == Operation::Profile && runFailures[k].empty() && e.problem.empty()) {
      // One row per reference point inside the sampled range; the points beyond it (wall values)
      // are drawn, not compared.
      const auto comparisons = compareProfile(e.curve, q.reference.data, q.tolerance);
      const std::size_t before = rows.size();
      for (std::size_t i = 0; i < comparisons.size(); ++i) {
        if (!comparisons[i]) continue;
        Row point = row;
        point.quantity = fmt::format("{}: {} = {:g}", q.name, q.xColumn, q.reference.data.x[i]);
        point.comparison = comparisons[i];
        point.at = q.reference.data.x[i];
        rows.push_back(point);
      }
      if (rows.size() == before) {
        row.note = fmt::format("no reference point inside the sampled range [{:g}, {:g}] of {}", e.curve.x.front(), e.curve.x.back(), q.xColumn);
        rows.push_back(row);
      }
      continue;
    }
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

}  // namespace gf::app::validation
