// `grainflow bench`: the benchmark executable it starts runs its thread team on the CPUs the
// OpenMP places name (not on the one place the launcher's own initial thread was bound to).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "run_helper.hpp"

using gf::testing::grainflow;

namespace {
/// The value of column `name` in the first result row of a tabular Google Benchmark output.
double tabularCounter(const std::string& output, const std::string& name) {
  std::istringstream lines(output);
  std::string line;
  int column = -1;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string word;
    std::vector<std::string> fields;
    while (words >> word) fields.push_back(word);
    if (!fields.empty() && fields[0] == "Benchmark") {
      for (std::size_t i = 0; i < fields.size(); ++i)
        if (fields[i] == name) column = static_cast<int>(i);
    } else if (column >= 0 && !fields.empty() && fields[0].rfind("BM_", 0) == 0) {
      // header: Benchmark Time CPU Iterations c1 c2 ...; row: name t unit cpu unit iterations v1 v2 ...
      const std::size_t at = static_cast<std::size_t>(column) + 2;
      if (at < fields.size()) return std::stod(fields[at]);
    }
  }
  return -1.0;
}
}  // namespace

TEST(BenchCommand, TeamRunsOnEveryOmpPlace) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "needs two CPUs";
  // Without places: the team may use both CPUs.
  const auto plain = grainflow("bench 'BM_TeamBarrier' --threads 2");
  if (plain.output.find("benchmark executable not found") != std::string::npos)
    GTEST_SKIP() << "built without the benchmarks (GRAINFLOW_BUILD_BENCH=OFF)";
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  EXPECT_EQ(tabularCounter(plain.output, "members"), 2.0) << plain.output;
  EXPECT_EQ(tabularCounter(plain.output, "team_cpus"), 2.0) << plain.output;
  // Bound to two places: one member per CPU. Before the launcher widened its mask, both members
  // inherited CPU 0 (team_cpus 1, 89 us per barrier instead of 0.4 us).
  const auto bound = gf::testing::runShell("OMP_PROC_BIND=true OMP_PLACES='{0},{1}' " + std::string(GRAINFLOW_BINARY) +
                                           " bench 'BM_TeamBarrier' --threads 2");
  ASSERT_EQ(bound.exitCode, 0) << bound.output;
  EXPECT_EQ(tabularCounter(bound.output, "members"), 2.0) << bound.output;
  EXPECT_EQ(tabularCounter(bound.output, "team_cpus"), 2.0) << bound.output;
}
