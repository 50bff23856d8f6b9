#pragma once
// The split of the contact sweep's rows into one contiguous block per thread, by estimated work
// (BlockSplit). The sweep itself: block_sweep.hpp; what the blocks exchange: partner_buffers.hpp.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dem/neighbour_list.hpp"
#include "dem/wall_contact_list.hpp"

namespace gf::dem {

/// Work-balanced split of the rows [0, n) into one contiguous block per thread (block t:
/// [start[t], start[t + 1])). The cost of a row is estimated from the lists and the positions at
/// their build (all restored by a restart): kRowCost per row (body forces, row sums) + 1 per
/// listed partner (the distance test) + kTouchingCost per pair touching at the build (gather,
/// contact law, scatter) + kWallCost per wall entry + kKickCost (the closing half kick, which
/// every thread applies to its block in the pass after the sweep: closingHalfKick).
/// Deterministic for a list and a thread count. The costs were fitted to per-thread CPU samples
/// of the contact phase on 2 threads, bubbling bed and settled bed (where the touching pairs are
/// unevenly spread over the rows: the row-count split gave the second thread 1.8 x the first's
/// samples in the bubbling bed, the first 1.15 x the second's in the settled bed); the inline kick
/// was first taken as free, and per-thread CPU time then showed the kicking block at 1.3-1.4 x the
/// others in the bubbling bed, 1.2 x in the settled bed; with 1.5 both were within 0.95-1.05.
/// (Those samples were taken with the kick inside the sweep; it is now a pass of its own over the
/// same blocks, so it is still charged to every block.)
struct BlockSplit {
  static constexpr double kRowCost = 1.0, kTouchingCost = 2.5, kWallCost = 1.0, kKickCost = 1.5;
  /// weight (optional, one per thread): block t gets the share weight[t] / sum of the cost
  /// (PartnerBuffers::speed: the measured relative speed of each thread); equal shares without.
  /// blockCost (optional): the modelled cost of each block.
  static void compute(const std::uint32_t* rowStart, const std::uint32_t* touchingStart,
                      const std::uint32_t* wallRowStart, std::size_t n, int team, std::vector<std::size_t>& start,
                      const double* weight = nullptr, std::vector<double>* blockCost = nullptr) {
    start.assign(static_cast<std::size_t>(team) + 1, 0);
    start[team] = n;
    // cumulative cost of rows [0, i)
    auto cost = [&](std::size_t i) {
      return (kRowCost + kKickCost) * static_cast<double>(i) + static_cast<double>(rowStart[i]) +
             (touchingStart ? kTouchingCost * static_cast<double>(touchingStart[i]) : 0.0) +
             (wallRowStart ? kWallCost * static_cast<double>(wallRowStart[i]) : 0.0);
    };
    if (team > 1 && n > 0) {
      auto firstRow = [&](auto&& reached) {  // first row where `reached` holds (it is monotone)
        std::size_t lo = 0, hi = n;
        while (lo < hi) {
          const std::size_t mid = lo + (hi - lo) / 2;
          if (reached(mid)) hi = mid;
          else lo = mid + 1;
        }
        return lo;
      };
      double weightSum = 0.0;
      for (int t = 0; t < team; ++t) weightSum += weight ? weight[t] : 1.0;
      const double total = cost(n);
      double before = 0.0;  // weights of the blocks before t
      for (int t = 1; t < team; ++t) {
        before += weight ? weight[t - 1] : 1.0;
        // (unweighted: the formula of before, whose bits the coupling's split keeps: threadBlocks)
        const double target = weight ? total * (before / weightSum) : t * (total / team);
        start[t] = std::max(start[t - 1], firstRow([&](std::size_t i) { return cost(i) >= target; }));
      }
    }
    if (blockCost) {
      blockCost->resize(static_cast<std::size_t>(team));
      for (int t = 0; t < team; ++t) (*blockCost)[t] = n > 0 ? cost(start[t + 1]) - cost(start[t]) : 0.0;
    }
  }
};

/// BlockSplit of the rows of `list` (and of the wall entries, with walls) for a team. Equal shares
/// without weights: a function of the lists (System::threadBlocks). The force loop's split starts
/// from it and then follows the threads' measured speeds (PartnerBuffers::speed as the weights).
inline void splitRowsAmongThreads(const NeighbourList& list, const WallContactList& wallList, bool withWalls,
                                  std::size_t n, int team, std::vector<std::size_t>& start,
                                  const double* weight = nullptr, std::vector<double>* blockCost = nullptr) {
  BlockSplit::compute(list.rowStart.data(), list.touchingStart.size() == n + 1 ? list.touchingStart.data() : nullptr,
                      withWalls ? wallList.rowStart.data() : nullptr, n, team, start, weight, blockCost);
}

}  // namespace gf::dem
