// BlockSplit: the contact sweep's rows are split into contiguous blocks of equal estimated cost.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "dem/block_split.hpp"
#include "dem/partner_buffers.hpp"

namespace gf::dem {
namespace {

// Cumulative counts (CSR offsets) of a per-row count.
std::vector<std::uint32_t> offsets(const std::vector<std::uint32_t>& perRow) {
  std::vector<std::uint32_t> start(perRow.size() + 1, 0);
  for (std::size_t i = 0; i < perRow.size(); ++i) start[i + 1] = start[i] + perRow[i];
  return start;
}

// The cost model of BlockSplit, row by row: every thread sweeps its rows and kicks them.
double blockCost(const std::vector<std::uint32_t>& partners, const std::vector<std::uint32_t>& touching,
                 const std::vector<std::uint32_t>& walls, std::size_t from, std::size_t to) {
  double cost = 0.0;
  for (std::size_t i = from; i < to; ++i)
    cost += BlockSplit::kRowCost + partners[i] + BlockSplit::kTouchingCost * touching[i] +
            BlockSplit::kWallCost * walls[i] + BlockSplit::kKickCost;
  return cost;
}

TEST(BlockSplit, BlocksCoverTheRowsAndCarryEqualCost) {
  // Dense rows first (a settled region), then sparse rows with wall contacts (a freeboard).
  const std::size_t n = 20000;
  std::vector<std::uint32_t> partners(n), touching(n), walls(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool dense = i < n / 2;
    partners[i] = dense ? 7 + static_cast<std::uint32_t>(i % 3) : 2 + static_cast<std::uint32_t>(i % 2);
    touching[i] = dense ? 3 : static_cast<std::uint32_t>(i % 4 == 0);
    walls[i] = dense ? 0 : static_cast<std::uint32_t>(i % 5 == 0);
  }
  const auto rowStart = offsets(partners), touchingStart = offsets(touching), wallStart = offsets(walls);
  for (int team : {1, 2, 3, 4}) {
    std::vector<std::size_t> start;
    BlockSplit::compute(rowStart.data(), touchingStart.data(), wallStart.data(), n, team, start);
    ASSERT_EQ(start.size(), static_cast<std::size_t>(team) + 1);
    EXPECT_EQ(start.front(), 0u);
    EXPECT_EQ(start.back(), n);
    std::vector<double> cost(team);
    for (int t = 0; t < team; ++t) {
      ASSERT_LE(start[t], start[t + 1]);
      cost[t] = blockCost(partners, touching, walls, start[t], start[t + 1]);
    }
    // One row costs at most ~20 units of ~2.3e5 in all: equal to 1e-3 of a share.
    double mean = 0.0;
    for (double c : cost) mean += c / team;
    for (int t = 0; t < team; ++t) EXPECT_NEAR(cost[t], mean, 1e-3 * mean) << "team " << team << " block " << t;
  }
}

TEST(BlockSplit, SameInputGivesTheSameBlocks) {
  std::vector<std::uint32_t> partners(5000, 6), touching(5000, 2);
  const auto rowStart = offsets(partners), touchingStart = offsets(touching);
  std::vector<std::size_t> a, b;
  BlockSplit::compute(rowStart.data(), touchingStart.data(), nullptr, partners.size(), 2, a);
  BlockSplit::compute(rowStart.data(), touchingStart.data(), nullptr, partners.size(), 2, b);
  EXPECT_EQ(a, b);
  // Uniform rows: two blocks of equal length.
  EXPECT_EQ(a[1], partners.size() / 2);
}

// Weighted shares (PartnerBuffers::speed): block t carries weight[t] / sum of the cost, and
// blockCost reports what each block carries.
TEST(BlockSplit, WeightsSetTheShares) {
  const std::size_t n = 20000;
  std::vector<std::uint32_t> partners(n), touching(n);
  for (std::size_t i = 0; i < n; ++i) {
    partners[i] = 3 + static_cast<std::uint32_t>(i % 7);
    touching[i] = static_cast<std::uint32_t>(i % 3);
  }
  const auto rowStart = offsets(partners), touchingStart = offsets(touching);
  const std::vector<double> weight = {0.5, 1.0, 2.5};
  std::vector<std::size_t> start;
  std::vector<double> reported;
  BlockSplit::compute(rowStart.data(), touchingStart.data(), nullptr, n, 3, start, weight.data(), &reported);
  const std::vector<std::uint32_t> noWalls(n, 0);
  double total = 0.0;
  for (int t = 0; t < 3; ++t) total += blockCost(partners, touching, noWalls, start[t], start[t + 1]);
  ASSERT_EQ(reported.size(), 3u);
  for (int t = 0; t < 3; ++t) {
    const double cost = blockCost(partners, touching, noWalls, start[t], start[t + 1]);
    EXPECT_NEAR(cost, total * weight[t] / 4.0, 1e-3 * total) << "block " << t;
    EXPECT_NEAR(reported[t], cost, 1e-9 * total) << "block " << t;
  }
  // Equal weights give the unweighted split.
  std::vector<std::size_t> equal, unweighted;
  const std::vector<double> ones = {1.0, 1.0, 1.0};
  BlockSplit::compute(rowStart.data(), touchingStart.data(), nullptr, n, 3, equal, ones.data());
  BlockSplit::compute(rowStart.data(), touchingStart.data(), nullptr, n, 3, unweighted);
  EXPECT_EQ(equal, unweighted);
}

// The speeds follow the measured sweeps: a thread that takes twice as long for its block's cost
// loses work, a single preempted sweep does not move them, and the speeds stay in their bounds.
TEST(PartnerBuffers, SpeedsFollowTheMeasuredSweeps) {
  PartnerBuffers buffers;
  buffers.speed = {1.0, 1.0};
  buffers.blockCost = {100.0, 100.0};
  buffers.sweepTime.assign(2, PartnerBuffers::SweepTimes{});
  auto measure = [&](double first, double second, double outlier) {
    buffers.sweepTime.assign(2, PartnerBuffers::SweepTimes{});
    for (int k = 0; k < 30; ++k) {
      buffers.recordSweep(0, first);
      buffers.recordSweep(1, k == 7 ? outlier : second);
    }
    buffers.sweepsTimed = 30;
    buffers.updateSpeeds(2);
  };
  // Equal sweeps and one preempted sweep of the second thread (50 x): nothing moves.
  measure(1e-3, 1e-3, 50e-3);
  EXPECT_DOUBLE_EQ(buffers.speed[0], 1.0);
  EXPECT_DOUBLE_EQ(buffers.speed[1], 1.0);
  // The second thread twice as slow: measured speeds 4/3 and 2/3; each update moves a quarter of
  // the way, so the speeds converge to them geometrically.
  for (int update = 0; update < 40; ++update) measure(1e-3, 2e-3, 2e-3);
  EXPECT_NEAR(buffers.speed[0], 4.0 / 3.0, 1e-3);
  EXPECT_NEAR(buffers.speed[1], 2.0 / 3.0, 1e-3);
  EXPECT_NEAR(buffers.speed[0] + buffers.speed[1], 2.0, 1e-12);
  // Too few sweeps timed: no update.
  buffers.sweepsTimed = PartnerBuffers::kTimedSweeps - 1;
  const std::vector<double> before = buffers.speed;
  buffers.updateSpeeds(2);
  EXPECT_EQ(buffers.speed, before);
  // Not adaptive (speeds fixed by a test): no update.
  buffers.adaptive = false;
  measure(1e-3, 1e-3, 1e-3);
  EXPECT_EQ(buffers.speed, before);
}

}  // namespace
}  // namespace gf::dem
