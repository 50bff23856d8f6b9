#pragma once
// A CSV time series (one file per monitor): header with units, rows kept in memory and the
// file rewritten atomically on flush, so a crash never leaves a torn file.
#include <string>
#include <vector>

#include "core/monitor.hpp"

namespace gf::io {

class CsvSeries {
 public:
  CsvSeries(std::string path, std::vector<MonitorColumn> columns);
  void addRow(double time, const std::vector<double>& values);
  void flush() const;
  /// On restart: keeps the rows of an existing file up to `time`.
  void resumeFrom(double time);
  const std::string& path() const { return path_; }
  std::size_t rows() const { return rows_.size(); }

 private:
  std::string path_;
  std::string header_;
  std::vector<std::string> rows_;
};

/// Parses a CSV written by CsvSeries: column names (with units) and values.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};
CsvTable readCsv(const std::string& path);

}  // namespace gf::io
