// The solvers' reductions (core/reduction.hpp) sum in the order their policy names: the results are
// compared bit for bit with the sums written out in that order, on terms whose sum depends on it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/parallel.hpp"
#include "core/reduction.hpp"

namespace gf {
namespace {

// Terms of very different sizes: any change of the order of the additions changes the bits.
std::vector<double> mixedTerms(std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = (i % 3 == 0 ? 1e16 : 1.0) * (i % 2 ? -1.0 : 1.0) + 0.1 * double(i);
  return v;
}

TEST(Reduction, OneThreadSumsInIndexOrderOrInFourInterleavedSums) {
  const std::vector<double> v = mixedTerms(103);
  const auto n = static_cast<std::int64_t>(v.size());
  auto term = [&](std::int64_t i) { return v[i]; };
  double sequential = 0.0;
  for (double x : v) sequential += x;
  double s[4] = {};
  std::int64_t i = 0;
  for (; i + 4 <= n; i += 4)
    for (int k = 0; k < 4; ++k) s[k] += v[i + k];
  for (; i < n; ++i) s[0] += v[i];
  const double interleaved = (s[0] + s[1]) + (s[2] + s[3]);
  ASSERT_NE(sequential, interleaved);  // (the terms tell the orders apart)
  EXPECT_EQ(globalSum(n, SumPolicy{1000, false, false}, term), sequential);
  EXPECT_EQ(globalSum(n, SumPolicy{0, true, false}, term), sequential);
  EXPECT_EQ(globalSum(n, SumPolicy{1000, false, true}, term), interleaved);
  EXPECT_EQ(serialSum4(n, term), interleaved);
}

TEST(Reduction, ThreadsSumFixedBlocksAddedInThreadOrder) {
  const int saved = threadCount();
  setThreadCount(2);
  const std::vector<double> v = mixedTerms(4099);
  const auto n = static_cast<std::int64_t>(v.size());
  double expected = 0.0;
  for (int t = 0; t < 2; ++t) {  // schedule(static): one contiguous block per thread
    const auto [begin, end] = threadBlock(n, t, 2, nullptr);
    double block = 0.0;
    for (std::int64_t i = begin; i < end; ++i) block += v[i];
    expected += block;
  }
  const double sum = globalSum(n, SumPolicy{16, false, true}, [&](std::int64_t i) { return v[i]; });
  setThreadCount(saved);
  EXPECT_EQ(sum, expected);
}

TEST(Reduction, TwoSumsInOnePassKeepTheOrderOfEach) {
  const std::vector<double> v = mixedTerms(37), w = mixedTerms(38);
  const auto n = static_cast<std::int64_t>(v.size());
  auto body = [&](std::int64_t i, double& a, double& b) {
    a += v[i];
    b += v[i] * w[i + 1];
  };
  double a[2] = {}, b[2] = {};
  for (std::int64_t i = 0; i < n; ++i) {
    a[i % 2] += v[i];
    b[i % 2] += v[i] * w[i + 1];
  }
  const auto [ia, ib] = globalSum2(n, SumPolicy{1000, false, true}, body);
  EXPECT_EQ(ia, a[0] + a[1]);
  EXPECT_EQ(ib, b[0] + b[1]);
  const auto [sa, sb] = globalSum2(n, SumPolicy{1000, false, false}, body);
  double ea = 0.0, eb = 0.0;
  for (std::int64_t i = 0; i < n; ++i) {
    ea += v[i];
    eb += v[i] * w[i + 1];
  }
  EXPECT_EQ(sa, ea);
  EXPECT_EQ(sb, eb);
}

TEST(Reduction, DotNormAndPartials) {
  const std::vector<double> a = {1.0, 2.0, 3.0}, b = {4.0, -5.0, 6.0};
  EXPECT_EQ(dot(a, b, SumPolicy{}), 12.0);
  EXPECT_EQ(norm(a, SumPolicy{}), std::sqrt(14.0));
  const std::vector<double> partial = mixedTerms(11);
  double inOrder = 0.0;
  for (double x : partial) inOrder += x;
  EXPECT_EQ(sumOfPartials(partial), inOrder);
  EXPECT_EQ(maxOfPartials({0.5, 3.0, 2.0}), 3.0);
  EXPECT_EQ(maxOfPartials({}), 0.0);
}

}  // namespace
}  // namespace gf
