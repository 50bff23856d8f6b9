#include "io/csv_series.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace gf::io {

CsvSeries::CsvSeries(std::string path, std::vector<MonitorColumn> columns) : path_(std::move(path)) {
  header_ = "time [s]";
  for (const MonitorColumn& c : columns) header_ += fmt::format(",{} [{}]", c.name, c.unit);
}

void CsvSeries::addRow(double time, const std::vector<double>& values) {
  std::string row = fmt::format("{:.12g}", time);
  for (double v : values) row += fmt::format(",{:.12g}", v);
  rows_.push_back(std::move(row));
  changed_ = true;
}

void CsvSeries::flush() {
  if (!changed_) return;
  std::string out = header_ + "\n";
  for (const std::string& r : rows_) out += r + "\n";
  writeFileAtomically(path_, out);
  changed_ = false;
}

void CsvSeries::resumeFrom(double time) {
  rows_.clear();
  changed_ = true;
  if (!std::filesystem::exists(path_)) return;
  std::istringstream lines(readFile(path_));
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    if (std::stod(line.substr(0, line.find(','))) <= time * (1.0 + 1e-12)) rows_.push_back(line);
  }
}

CsvTable readCsv(const std::string& path) {
  CsvTable table;
  std::istringstream lines(readFile(path));
  std::string line;
  if (!std::getline(lines, line)) throw Error(fmt::format("CSV '{}' is empty", path));
  std::istringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');) table.header.push_back(cell);
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace gf::io
