// The ranks' layout (parallel/decomposition.hpp) for any rank count, in one process: automatic
// layouts minimise the cut area, ownership is a pure function of position, boxes tile the domain,
// periodic axes wrap, and bad layouts are refused.
#include "parallel/decomposition.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "domain_box.hpp"

namespace gf::parallel {
namespace {

using testing::box;

TEST(Decomposition, AutoLayoutCutsAcrossTheLongAxis) {
  // A tall column: cuts across z have the smallest area.
  EXPECT_EQ(Decomposition::autoLayout(box({0.03, 0.03, 0.12}), 2), (Layout{1, 1, 2}));
  EXPECT_EQ(Decomposition::autoLayout(box({0.03, 0.03, 0.12}), 4), (Layout{1, 1, 4}));
  // A cube on 8 ranks: 2 x 2 x 2 (area 3 faces) beats 8 slabs (7 faces).
  EXPECT_EQ(Decomposition::autoLayout(box({1, 1, 1}), 8), (Layout{2, 2, 2}));
  // A grid of 4 cells along z cannot be split there (each box needs kMinCellsPerRank = 3 cells
  // along a split axis); the long z cuts are left for x and y (ties: the first layout in the order
  // of increasing px, then py).
  EXPECT_EQ(Decomposition::autoLayout(box({1, 1, 10}), 8, {64, 64, 4}), (Layout{2, 4, 1}));
  EXPECT_EQ(Decomposition::autoLayout(box({1, 1, 10}), 2, {64, 64, 6}), (Layout{1, 1, 2}));  // 3 cells each
  // A periodic axis split in two has two cuts, a bounded one one: x (2 x 1.1) loses to z (1.2).
  EXPECT_EQ(Decomposition::autoLayout(box({1.2, 1, 1.1}, {true, false, false}), 2), (Layout{1, 1, 2}));
}

TEST(Decomposition, BoxesTileTheDomainAndOwnershipFollowsPosition) {
  const Domain d = box({1.0, 2.0, 3.0});
  for (int ranks : {1, 2, 3, 4, 6, 12}) {
    double volume = 0.0;
    for (int r = 0; r < ranks; ++r) {
      const Decomposition dec(d, {0, 0, 0}, ranks, r);
      const Vec3 lo = dec.lower(), hi = dec.upper();
      volume += (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
      EXPECT_EQ(dec.ownerOf(0.5 * (lo + hi)), r);
      EXPECT_EQ(dec.ownerOf(lo), r);  // the lower faces belong to the box
    }
    EXPECT_NEAR(volume, 6.0, 1e-12) << ranks;
  }
  // Positions outside a bounded axis go to the nearest box.
  const Decomposition dec(d, {1, 1, 2}, 2, 0);
  EXPECT_EQ(dec.ownerOf({0.5, 1.0, -0.1}), 0);
  EXPECT_EQ(dec.ownerOf({0.5, 1.0, 3.1}), 1);
  EXPECT_EQ(dec.ownerOf({0.5, 1.0, 3.0}), 1);  // the upper face of the last box
}

TEST(Decomposition, GridCutsFollowCells) {
  // 10 cells on 3 ranks: 4, 3, 3 cells.
  const Domain d = box({1.0, 1.0, 1.0});
  const int expected[3] = {4, 3, 3};
  int offset = 0;
  for (int r = 0; r < 3; ++r) {
    const Decomposition dec(d, {3, 1, 1}, 3, r, {10, 5, 5});
    EXPECT_EQ(dec.cellCount()[0], expected[r]);
    EXPECT_EQ(dec.cellOffset()[0], offset);
    EXPECT_NEAR(dec.lower().x, 0.1 * offset, 1e-15);
    offset += expected[r];
  }
}

TEST(Decomposition, SidesNeighboursAndPeriodicDistances) {
  const Domain d = box({2.0, 1.0, 1.0}, {true, false, false});
  const Decomposition left(d, {2, 1, 1}, 2, 0);
  EXPECT_EQ(left.side(0, -1), Side::Shared);  // periodic wrap to rank 1
  EXPECT_EQ(left.side(0, +1), Side::Shared);
  EXPECT_EQ(left.side(1, -1), Side::Physical);
  EXPECT_EQ(left.neighbourAcross(0, -1), 1);
  EXPECT_EQ(left.neighbourRanks(), (std::vector<int>{1}));
  // x = 1.95 lies in rank 1's box; its periodic image is 0.05 from rank 0's lower face.
  EXPECT_NEAR(left.distanceToBox({1.95, 0.5, 0.5}, 0).x, 0.05, 1e-12);
  EXPECT_NEAR(left.distanceToBox({1.95, 0.5, 0.5}, 1).x, 0.0, 1e-15);
  EXPECT_NEAR(left.distanceToBox({0.5, 1.5, 0.5}, 1).y, 0.5, 1e-15);  // (bounded y: no image)
  const Decomposition single(d, {1, 1, 1}, 1, 0);
  EXPECT_EQ(single.side(0, -1), Side::Periodic);
  EXPECT_TRUE(single.neighbourRanks().empty());
}

TEST(Decomposition, RefusesLayoutsThatDoNotFit) {
  const Domain d = box({1.0, 1.0, 1.0});
  EXPECT_THROW(Decomposition(d, {3, 1, 1}, 2, 0), std::invalid_argument);      // 3 boxes for 2 ranks
  EXPECT_THROW(Decomposition(d, {4, 1, 1}, 4, 0, {2, 8, 8}), std::invalid_argument);  // 4 ranks, 2 cells
  EXPECT_THROW(Decomposition::autoLayout(d, 7, {2, 2, 1}), std::invalid_argument);
}


TEST(Decomposition, BalancedCutsEvenOutThePlanesCosts) {
  // 12 planes, the first 4 twice as costly: total 4 x 3 + 8 x 1.5 = 24, half after plane 4.
  std::vector<double> cost(12, 1.5);
  for (int i = 0; i < 4; ++i) cost[static_cast<std::size_t>(i)] = 3.0;
  EXPECT_EQ(Decomposition::balancedCuts(cost, 2, 3), (std::vector<int>{0, 4, 12}));
  // uniform planes: even parts
  EXPECT_EQ(Decomposition::balancedCuts(std::vector<double>(12, 1.0), 3, 3), (std::vector<int>{0, 4, 8, 12}));
  // every part keeps its minimum even where the cost would put the cut nearer the end
  std::vector<double> front(12, 0.0);
  front[0] = 100.0;
  EXPECT_EQ(Decomposition::balancedCuts(front, 2, 3), (std::vector<int>{0, 3, 12}));
  EXPECT_THROW(Decomposition::balancedCuts(std::vector<double>(5, 1.0), 2, 3), std::invalid_argument);
}

TEST(Decomposition, WithCellCutsMovesTheBoxesAndKeepsTheNeighbours) {
  const Domain d = box({1.0, 1.0, 2.4});
  const Decomposition even(d, {1, 1, 2}, 2, 1, {4, 4, 24});
  EXPECT_EQ(even.cellOffset()[2], 12);
  const Decomposition moved = even.withCellCuts({std::vector<int>{0, 4}, std::vector<int>{0, 4}, std::vector<int>{0, 6, 24}});
  EXPECT_EQ(moved.cellOffset()[2], 6);
  EXPECT_EQ(moved.cellCount()[2], 18);
  EXPECT_NEAR(moved.lower()[2], 0.6, 1e-12);
  EXPECT_EQ(moved.ownerOf({0.5, 0.5, 0.5}), 0);
  EXPECT_EQ(moved.ownerOf({0.5, 0.5, 0.7}), 1);
  EXPECT_EQ(moved.neighbourRanks(), even.neighbourRanks());
  EXPECT_THROW(even.withCellCuts({std::vector<int>{0, 4}, std::vector<int>{0, 4}, std::vector<int>{0, 30, 24}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace gf::parallel
