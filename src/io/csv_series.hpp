#pragma once
// A CSV time series (one file per monitor): header with units, rows kept in memory and the
// file rewritten whole and atomically on flush (io/atomic_file.hpp), not appended to: a crash or a
// kill at any moment leaves the previous complete file, never a torn row. A flush costs a pass
// over the rows (about 50 bytes each), and the run flushes at most every run.progress_interval
// of wall time.
#include <string>
#include <vector>

#include "core/monitor.hpp"

namespace gf::io {

class CsvSeries {
 public:
  CsvSeries(std::string path, std::vector<MonitorColumn> columns);
  void addRow(double time, const std::vector<double>& values);
  /// Writes the file if rows were added or dropped since the last flush (or it was never written).
  void flush();
  /// On restart: keeps the rows of an existing file up to `time` (the rows a run wrote after its
  /// checkpoint are dropped here and sampled again).
  void resumeFrom(double time);
  const std::string& path() const { return path_; }
  std::size_t rows() const { return rows_.size(); }

 private:
  std::string path_;
  std::string header_;
  std::vector<std::string> rows_;
  bool changed_ = true;  // rows differ from the file's (or the file is not written yet)
};

/// Parses a CSV written by CsvSeries: column names (with units) and values.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
};
CsvTable readCsv(const std::string& path);

}  // namespace gf::io
