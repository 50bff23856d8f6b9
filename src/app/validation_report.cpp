#include "app/validation_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "app/plot.hpp"
#include "io/atomic_file.hpp"

namespace gf::app::validation {

namespace fs = std::filesystem;

namespace {

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

std::string formatTolerance(const Tolerance& t) {
  if (t.lowerBound) return ">= reference";
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

}  // namespace

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

namespace {

std::string csvCell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string resultsCsv(const std::vector<Row>& rows) {
  std::string out = "item,run,quantity,operation,reference,grainflow,error,tolerance,tolerance_type,pass,note\n";
  for (const Row& r : rows)
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", csvCell(r.item), csvCell(r.runLabel), csvCell(r.quantity), r.operation,
                       r.comparison ? fmt::format("{:.10g}", r.comparison->reference) : "",
                       r.comparison ? fmt::format("{:.10g}", r.comparison->computed) : "",
                       r.comparison ? fmt::format("{:.6g}", r.comparison->error) : "", fmt::format("{:.6g}", r.tolerance.value),
                       r.tolerance.lowerBound ? "lower_bound" : r.tolerance.relative ? "relative" : "absolute", r.pass() ? 1 : 0, csvCell(r.note));
  return out;
}

namespace {

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
    out += fmt::format("| [`{}`]({}#{}) | {}{} | {}/{} | {} |\n", items[i].name, linkPrefix, items[i].name, items[i].title,
                       items[i].reportQuick ? " (quick settings)" : "", passed, rowsPerItem[i].size(), ok ? "pass" : "**FAIL**");
  }
  return out;
}

}  // namespace

Provenance treeProvenance(const std::string& repository) {
  Provenance p;
  p.commit = commandOutput(fmt::format("git -C {} rev-parse --short=12 HEAD 2>/dev/null", shellQuote(repository)));
  if (p.commit.empty()) return p;
  std::istringstream lines(commandOutput(fmt::format(
      "git -C {} status --porcelain --untracked-files=all -- . ':!docs/validation.md' ':!docs/img' ':!README.md' 2>/dev/null",
      shellQuote(repository))));
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) p.changes.push_back(line);
  return p;
}

namespace {

/// The figure files a report links to: img/<name>.png.
std::set<std::string> linkedFigures(const std::string& markdown) {
  std::set<std::string> out;
  static const std::regex link(R"(\(img/([^)/]+\.png)\))");
  for (auto it = std::sregex_iterator(markdown.begin(), markdown.end(), link); it != std::sregex_iterator(); ++it) out.insert((*it)[1]);
  return out;
}

std::string provenanceText(const Provenance& p) {
  if (p.commit.empty()) return "unknown (not a git work tree)";
  if (p.changes.empty()) return fmt::format("`{}`", p.commit);
  std::vector<std::string> paths;
  for (std::size_t i = 0; i < p.changes.size() && i < 5; ++i)  // porcelain lines: "XY path"
    paths.push_back(fmt::format("`{}`", p.changes[i].size() > 3 ? p.changes[i].substr(3) : p.changes[i]));
  if (p.changes.size() > 5) paths.push_back(fmt::format("{} more", p.changes.size() - 5));
  return fmt::format("`{}` (with uncommitted changes: {})", p.commit, fmt::join(paths, ", "));
}

}  // namespace

void writeDocs(const std::string& docsDirectory, const std::string& repository, const std::vector<Item>& items,
               const std::vector<std::vector<Row>>& rowsPerItem, const std::vector<ItemOutcome>& outcomes, double wall, int threads,
               const Provenance& provenance) {
  const fs::path docs(docsDirectory), img = docs / "img";
  fs::create_directories(img);
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::string md = "# Validation report\n\n";
  md += "<!-- Generated by `grainflow validate` (full mode, all items). Do not edit: rerun it. -->\n\n";
  md += "Each item is data under `validation/<item>/` (format: [validation-format.md](validation-format.md)): a case file, the "
        "reference (value or CSV with its source), the extraction from the monitor CSVs and the tolerance. Run them with "
        "`grainflow validate` (all items, this report) or `grainflow validate --quick [NAME...]` (reduced, as in ctest).\n\n";
  md += fmt::format("- Date: {}\n- Commit: {}\n- Machine: `{}`\n- CPU: {}\n- Threads: {}; total wall time {:.1f} s\n\n", date,
                    provenanceText(provenance), commandOutput("uname -a"), cpuModel(), threads, wall);
  md += "## Summary\n\n" + summaryTable(items, rowsPerItem, outcomes, "") + "\n";
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& item = items[i];
    md += fmt::format("## `{}`\n\n**{}**", item.name, item.title);
    md += item.description.empty() ? "\n\n" : fmt::format(" — {}\n\n", item.description);
    // the case relative to the source tree (validation/<item>/case.yaml, or an example case of cases/)
    const fs::path root = fs::weakly_canonical(fs::path(item.directory)).parent_path().parent_path();
    const std::string caseLink = fs::relative(fs::weakly_canonical(fs::path(item.caseFile)), root).generic_string();
    md += fmt::format("Case: [`{0}`](../{0})", caseLink);
    if (!item.sweepKey.empty()) {
      std::vector<std::string> values;
      for (const RunPoint& r : item.runs) values.push_back(fmt::format("{:g}", r.x));
      md += fmt::format("; sweep `{}` = {}", item.sweepKey, fmt::join(values, ", "));
    }
    md += fmt::format("; wall time {:.1f} s.\n\n", outcomes[i].wallSeconds);
    if (item.reportQuick)
      md += fmt::format("*Run in this report with its `--quick` settings and tolerances (`report_quick`): its full run takes "
                        "hours on the report's machine. `grainflow validate {}` runs it in full.*\n\n",
                        item.name);
    for (const Quantity& q : item.quantities) {
      const std::string across = q.across == AcrossRuns::LogLogSlope       ? ", log-log slope over the runs"
                                 : q.across == AcrossRuns::RichardsonOrder ? ", observed order from the last three runs (Richardson)"
                                 : q.across == AcrossRuns::MinIncrement    ? ", smallest increase between the runs"
                                 : q.across == AcrossRuns::GapClosed       ? ", share of the first run's distance from the last closed by the second"
                                                                           : "";
      const std::string quick = q.quickTolerance ? fmt::format("; tolerance in --quick mode {}", formatTolerance(*q.quickTolerance)) : "";
      if (q.operation == Operation::Profile)
        md += fmt::format("- `{}`: profile of `{}` over `{}` in `{}.csv` at its last sample time, compared at each reference point "
                          "inside the sampled range; reference: {}{}\n",
                          q.name, q.column, q.xColumn, q.monitor, q.reference.source, quick);
      else
        md += fmt::format("- `{}`: {} of `{}` in `{}.csv`{}; reference: {}{}\n", q.name, operationName(q.operation), q.column, q.monitor,
                          across, q.reference.source, quick);
    }
    md += fmt::format("\n{}\n", markdownTable(rowsPerItem[i]));
    for (const std::string& png : outcomes[i].plots) {
      std::error_code ec;
      const fs::path target = img / fs::path(png).filename();
      if (!fs::exists(png)) continue;
      fs::copy_file(png, target, fs::copy_options::overwrite_existing, ec);
      if (!ec) md += fmt::format("![{}](img/{})\n\n", item.name, target.filename().string());
    }
  }
  // Figures the previous report linked and this one does not (renamed or merged quantities) go,
  // unless the README shows them too.
  const fs::path report = docs / "validation.md";
  const std::set<std::string> before = fs::exists(report) ? linkedFigures(io::readFile(report.string())) : std::set<std::string>{};
  const std::set<std::string> after = linkedFigures(md);
  const fs::path readmePath = fs::path(repository) / "README.md";
  const std::string readmeText = fs::exists(readmePath) ? io::readFile(readmePath.string()) : std::string();
  io::writeFileAtomically(report.string(), md);
  std::printf("wrote %s\n", report.c_str());
  for (const std::string& name : before) {
    std::error_code ec;
    if (!after.count(name) && readmeText.find("img/" + name) == std::string::npos && fs::remove(img / name, ec))
      std::printf("removed %s (no longer in the report)\n", (img / name).c_str());
  }

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

}  // namespace gf::app::validation
