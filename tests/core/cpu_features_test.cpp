#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "core/cpu_features.hpp"

namespace {

// The CPU flags the kernel reports (first "flags" line of /proc/cpuinfo); empty elsewhere.
std::set<std::string> procCpuFlags() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    std::set<std::string> flags;
    for (std::string w; words >> w;) flags.insert(w);
    return flags;
  }
  return {};
}

}  // namespace

// cpuHas names the same sets as the kernel's flags (a swapped or missing feature in a set would
// send a kernel down a path the CPU cannot run, or keep it off one it can).
TEST(CpuFeatures, SetsMatchTheKernelsCpuFlags) {
#if defined(GF_X86_SIMD)
  const std::set<std::string> flags = procCpuFlags();
  if (flags.empty()) GTEST_SKIP() << "no /proc/cpuinfo flags on this system";
  const bool avx2 = flags.count("avx2") > 0, avx512f = flags.count("avx512f") > 0,
             avx512vl = flags.count("avx512vl") > 0;
  EXPECT_EQ(gf::cpuHas(gf::InstructionSet::Avx2), avx2);
  EXPECT_EQ(gf::cpuHas(gf::InstructionSet::Avx512fAvx2), avx512f && avx2);
  EXPECT_EQ(gf::cpuHas(gf::InstructionSet::Avx512fVl), avx512f && avx512vl);
#else
  EXPECT_FALSE(gf::cpuHas(gf::InstructionSet::Avx2));
  EXPECT_FALSE(gf::cpuHas(gf::InstructionSet::Avx512fVl));
#endif
}

// A form runs only where the CPU has its set and no test switched it off.
TEST(CpuFeatures, VectorFormFollowsTheCpuAndTheSwitch) {
  for (const gf::InstructionSet set :
       {gf::InstructionSet::Avx2, gf::InstructionSet::Avx512fAvx2, gf::InstructionSet::Avx512fVl}) {
    gf::VectorForm form(set);
    EXPECT_EQ(form.enabled(), gf::cpuHas(set));
    form.allow(false);
    EXPECT_FALSE(form.enabled());
    form.allow(true);
    EXPECT_EQ(form.enabled(), gf::cpuHas(set));
  }
}

// PREFETCHW is reported as the kernel's "3dnowprefetch" flag (CPUID 0x80000001 ECX bit 8); the
// request itself changes no memory (a line of a live array is still read back unchanged).
TEST(CpuFeatures, PrefetchForWriteMatchesTheKernelsFlagAndChangesNothing) {
#if defined(GF_X86_SIMD)
  const std::set<std::string> flags = procCpuFlags();
  if (!flags.empty()) {
    EXPECT_EQ(gf::cpuHasPrefetchW(), flags.count("3dnowprefetch") > 0);
  }
#else
  EXPECT_FALSE(gf::cpuHasPrefetchW());
#endif
  double values[16];
  for (int i = 0; i < 16; ++i) values[i] = 0.5 * i;
  if (gf::cpuHasPrefetchW())
    for (int i = 0; i < 16; i += 8) gf::prefetchForWrite(values + i);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(values[i], 0.5 * i);
}
