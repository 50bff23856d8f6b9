#include "app/plot.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "app/cli.hpp"

namespace gf::app {

namespace fs = std::filesystem;

std::string shellQuote(const std::string& word) {
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

namespace {
int shellStatus(const std::string& command) {
  const int status = std::system(command.c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

PlotTool findPlotTool(const std::string& repositoryHint) {
  PlotTool tool;
  std::vector<fs::path> scripts;
  if (const char* env = std::getenv("GRAINFLOW_PLOT_SCRIPT")) scripts.emplace_back(env);
  if (!repositoryHint.empty()) scripts.push_back(fs::path(repositoryHint) / "tools" / "plot.py");
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    scripts.push_back(self.parent_path().parent_path() / "tools" / "plot.py");
    scripts.push_back(self.parent_path().parent_path() / "share" / "grainflow" / "plot.py");
  }
  scripts.push_back(fs::path(GRAINFLOW_SOURCE_DIR) / "tools" / "plot.py");
  for (const fs::path& s : scripts)
    if (fs::is_regular_file(s, ec)) {
      tool.script = s.string();
      break;
    }
  if (tool.script.empty()) {
    tool.problem = "plot script tools/plot.py not found (set GRAINFLOW_PLOT_SCRIPT)";
    return tool;
  }
  std::vector<std::string> pythons;
  if (const char* env = std::getenv("GRAINFLOW_PYTHON")) {
    pythons.emplace_back(env);  // only this one when given
  } else {
    pythons.emplace_back("python3");
    pythons.emplace_back("/usr/bin/python3");  // Debian's, when python3 on PATH is another (pyenv, venv)
  }
  bool anyPython = false;
  for (const std::string& python : pythons) {
    const int status = shellStatus(shellQuote(python) + " -c 'import matplotlib' >/dev/null 2>&1");
    if (status == 0) {
      tool.python = python;
      return tool;
    }
    if (status != 127) anyPython = true;
  }
  tool.problem = anyPython ? "python3 cannot import matplotlib" : "python3 not found";
  return tool;
}

int runPlotScript(const PlotTool& tool, const std::vector<std::string>& arguments) {
  std::string command = shellQuote(tool.python) + " " + shellQuote(tool.script);
  for (const std::string& a : arguments) {
    command += ' ';
    command += shellQuote(a);
  }
  std::fflush(stdout);
  return shellStatus("MPLBACKEND=Agg " + command);
}

int plotRunOutput(const std::string& outputDirectory) {
  std::error_code ec;
  if (!fs::is_directory(outputDirectory, ec)) {
    std::fprintf(stderr, "grainflow: '%s' is not a directory (give the output directory of a run)\n", outputDirectory.c_str());
    return kExitIo;
  }
  bool anyCsv = false;
  for (const auto& entry : fs::directory_iterator(outputDirectory, ec))
    if (entry.path().extension() == ".csv") anyCsv = true;
  if (!anyCsv) {
    std::fprintf(stderr, "grainflow: no monitor CSV in '%s' (add 'monitors:' to the case)\n", outputDirectory.c_str());
    return kExitIo;
  }
  const PlotTool tool = findPlotTool();
  if (!tool.available()) {
    std::fprintf(stderr, "grainflow: cannot plot: %s; %s\n", tool.problem.c_str(), kPlotInstallHint);
    return kExitIo;
  }
  if (runPlotScript(tool, {"monitors", outputDirectory}) != 0) {
    std::fprintf(stderr, "grainflow: %s failed on '%s'\n", tool.script.c_str(), outputDirectory.c_str());
    return kExitIo;
  }
  return kExitOk;
}

}  // namespace gf::app
