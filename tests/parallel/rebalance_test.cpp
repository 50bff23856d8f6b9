// Recursive coordinate bisection (parallel/rebalance.hpp, Zoltan RCB) on one rank into several
// parts: the boxes tile the domain, hold equal shares of the points, and the same points given in
// another order give the same boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "parallel/rebalance.hpp"

namespace gf::parallel {
namespace {

TEST(Rebalance, ImbalanceIsMaxOverMean) {
  EXPECT_DOUBLE_EQ(imbalance({1, 1, 1, 1}), 1.0);
  EXPECT_DOUBLE_EQ(imbalance({4, 0, 0, 0}), 4.0);
  EXPECT_DOUBLE_EQ(imbalance({3, 1}), 1.5);
  EXPECT_DOUBLE_EQ(imbalance({0, 0}), 1.0);
}

TEST(Rebalance, BisectionTilesTheDomainWithEqualShares) {
  Domain d;
  d.min = {0, 0, 0};
  d.max = {0.03, 0.03, 0.12};
  // A bed in the lowest quarter of a column: cuts across z alone would leave three empty slabs.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int count = 4000, parts = 4;
  std::vector<std::int64_t> ids(count);
  std::vector<Vec3> x(count);
  for (int i = 0; i < count; ++i) {
    ids[i] = i;
    x[i] = {0.03 * u(random), 0.03 * u(random), 0.03 * u(random)};
  }
  const std::vector<double> weights(count, 1.0);
  const std::vector<Box> boxes = bisect(d, ids, x, weights, parts);
  ASSERT_EQ(boxes.size(), static_cast<std::size_t>(parts));
  const Decomposition dec(d, boxes, 0, 0.003);  // throws unless the boxes tile the domain
  std::vector<double> load(parts, 0.0);
  for (const Vec3& p : x) load[static_cast<std::size_t>(dec.ownerOf(p))] += 1.0;
  EXPECT_LT(imbalance(load), 1.05);
  EXPECT_GT(dec.smallestBoxWidth(), 0.005);
  // The same points in another order: the same boxes.
  std::vector<std::size_t> order(count);
  for (int i = 0; i < count; ++i) order[i] = static_cast<std::size_t>(i);
  std::shuffle(order.begin(), order.end(), random);
  std::vector<std::int64_t> ids2;
  std::vector<Vec3> x2;
  for (std::size_t i : order) {
    ids2.push_back(ids[i]);
    x2.push_back(x[i]);
  }
  const std::vector<Box> again = bisect(d, ids2, x2, weights, parts);
  for (int r = 0; r < parts; ++r) {
    EXPECT_EQ(again[r].lower, boxes[r].lower);
    EXPECT_EQ(again[r].upper, boxes[r].upper);
  }
}

}  // namespace
}  // namespace gf::parallel
