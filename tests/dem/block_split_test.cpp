// BlockSplit: the contact sweep's rows are split into contiguous blocks of equal estimated cost.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "dem/contact_kernel.hpp"

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

}  // namespace
}  // namespace gf::dem
