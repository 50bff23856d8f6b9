#pragma once
// What the threads of the contact sweep exchange (PartnerBuffers): the logs of the contributions
// to rows of other blocks, the rows that receive them, and the split of the rows that follows the
// threads' measured speed. The order in which the logs are added: contact_kernel.hpp.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"
#include "dem/block_split.hpp"
#include "dem/neighbour_list.hpp"
#include "dem/wall_contact_list.hpp"

namespace gf::dem {

/// One contribution to a particle's force and torque, kept in sweep order (PartnerBuffers).
struct LoggedContribution {
  Vec3 force, torque;  // added to the particle's force and torque
  std::uint32_t particle;
};

/// What the threads of the contact sweep exchange, and the split of the rows among them.
///
/// Summation order, the same on any split and any thread count: a particle's force is its body
/// force, plus the contributions of the rows before it in row order (half list: partners j > i),
/// plus its own row's sum, plus its wall contacts, added one at a time, exactly as one thread adds
/// them. A thread writes the forces of the rows of its block (block t: [blockStart[t],
/// blockStart[t + 1])) directly, except for its rows that receive contributions from earlier
/// blocks (`receives`, from the list at its build: a superset of those touched): for those it
/// logs its own contributions in sweep order (`deferred[t]`), and it logs its contributions to
/// rows of later blocks (`outgoing[t]`). After the barrier, thread t starts each of its receiving
/// rows from the body force its sweep set, adds the outgoing logs of the blocks before it (block
/// by block, each in sweep order, that is in row order), then its own deferred log. So the DEM
/// trajectory does not depend on the split: the split can follow the measured speed of each
/// thread (`speed`) without breaking reproducibility.
///
/// A row that receives nothing from earlier blocks has its final force when its block's sweep
/// completes it.
struct PartnerBuffers {
  std::vector<std::vector<LoggedContribution>> outgoing;  // per thread: to rows of later blocks
  std::vector<std::vector<LoggedContribution>> deferred;  // per thread: to its own receiving rows
  std::vector<std::size_t> blockStart;
  std::vector<std::uint8_t> receives;                // per particle: listed by a row of an earlier block
  std::vector<std::vector<std::uint32_t>> received;  // per thread: its rows that receive
  std::uint64_t receiversOfList = ~std::uint64_t{0};  // NeighbourList::version they were found for
  std::vector<std::size_t> receiversOfBlocks;         // and blockStart

  // Split following the threads' measured speed (only the speed depends on it).
  /// Relative speed of each thread of the team (mean 1): block t gets the share speed[t] / team of
  /// the modelled cost (BlockSplit). Updated at each new split (with each list build, and every
  /// kResplitSweeps sweeps between) from the sweep times since the last.
  std::vector<double> speed;
  std::vector<double> blockCost;  // modelled cost of each block of the current split
  struct alignas(64) SweepTimes {  // (own lines per thread: each writes its own)
    std::array<double, 64> seconds;  // the sweeps since the split was set (the first 64)
    int count = 0;
  };
  std::vector<SweepTimes> sweepTime;
  std::uint64_t splitOfList = ~std::uint64_t{0};  // NeighbourList::version the split was set for
  std::size_t splitOfRows = 0;
  bool adaptive = true;  // false: the speeds stay as set (tests set skewed ones)
  /// Steps (sweeps) a split must have been timed before its times move the speeds.
  static constexpr int kTimedSweeps = 4, kResplitSweeps = 64;
  int sweepsTimed = 0;
  /// How far a new measurement moves the speed (the rest is the previous speed), and the range
  /// a speed is kept in.
  static constexpr double kSpeedUpdate = 0.25, kSlowest = 0.5, kFastest = 2.0;

  std::size_t blockEnd(int t) const { return blockStart[t + 1]; }
  void findReceivers(const NeighbourList& list, std::size_t n, int threads) {
    receives.assign(n, 0);
    received.resize(static_cast<std::size_t>(threads));
    const std::uint32_t* rowStart = list.rowStart.data();
    const std::uint32_t* partner = list.partner.data();
    for (int t = 0; t + 1 < threads; ++t) {
      const std::size_t end = blockEnd(t);
      for (std::size_t i = blockStart[t]; i < end; ++i)
        for (std::uint32_t k = rowStart[i + 1]; k > rowStart[i];) {  // ascending partners: the far ones last
          const std::uint32_t j = partner[--k];
          if (j < end) break;
          receives[j] = 1;
        }
    }
    for (int t = 0; t < threads; ++t) {
      received[t].clear();
      if (t > 0)
        for (std::size_t i = blockStart[t]; i < blockEnd(t); ++i)
          if (receives[i]) received[t].push_back(static_cast<std::uint32_t>(i));
    }
    receiversOfList = list.version;
    receiversOfBlocks = blockStart;
  }
  /// A thread's typical sweep since the split was set: the mean of its sweeps, leaving out those
  /// above 1.5 x their median (a thread preempted on a shared machine: one sweep slowed many times
  /// over). The mean, not the fastest or the median: a thread that is slower in one step of a few
  /// (the one after a coupling step, whose work left other data in its caches) holds the team
  /// back in that step.
  static double typicalSweep(const SweepTimes& times) {
    const int count = std::min<int>(times.count, static_cast<int>(times.seconds.size()));
    if (count == 0) return 0.0;
    std::array<double, 64> sorted;
    std::copy(times.seconds.begin(), times.seconds.begin() + count, sorted.begin());
    std::nth_element(sorted.begin(), sorted.begin() + count / 2, sorted.begin() + count);
    const double limit = 1.5 * sorted[count / 2];
    double sum = 0.0;
    int kept = 0;
    for (int k = 0; k < count; ++k)
      if (times.seconds[k] <= limit) {
        sum += times.seconds[k];
        ++kept;
      }
    return sum / kept;
  }
  /// The speeds from the sweep times since the split was set: a thread that swept its block's
  /// modelled cost in less time is faster. A measurement moves the speed a quarter of the way
  /// (kSpeedUpdate): single windows of a few dozen sweeps are noisy on a shared machine.
  void updateSpeeds(int team) {
    if (!adaptive || sweepsTimed < kTimedSweeps || speed.size() != static_cast<std::size_t>(team)) return;
    std::vector<double> measured(static_cast<std::size_t>(team));
    double mean = 0.0;
    for (int t = 0; t < team; ++t) {
      const double seconds = typicalSweep(sweepTime[t]);
      if (seconds <= 0.0 || blockCost[t] <= 0.0) return;
      measured[t] = blockCost[t] / seconds;
      mean += measured[t] / team;
    }
    double sum = 0.0;
    for (int t = 0; t < team; ++t) {
      const double blended = (1.0 - kSpeedUpdate) * speed[t] + kSpeedUpdate * measured[t] / mean;
      speed[t] = std::clamp(blended, kSlowest, kFastest);
      sum += speed[t];
    }
    for (double& v : speed) v *= team / sum;
  }
  void prepare(int threads, std::size_t n, const NeighbourList& list, const WallContactList& wallList, bool withWalls) {
    if (speed.size() != static_cast<std::size_t>(threads)) {
      speed.assign(static_cast<std::size_t>(threads), 1.0);
      sweepsTimed = 0;
      splitOfList = ~std::uint64_t{0};
    }
    const bool listChanged =
        list.version != splitOfList || n != splitOfRows || blockStart.size() != static_cast<std::size_t>(threads) + 1;
    if (!listChanged) ++sweepsTimed;  // (the last sweep ran with this split)
    // A new split with each list, and every kResplitSweeps sweeps in between (a settled bed keeps
    // its lists for thousands of steps); receivers are found again only where it moved.
    if (listChanged || (adaptive && threads > 1 && sweepsTimed >= kResplitSweeps)) {
      updateSpeeds(threads);
      splitRowsAmongThreads(list, wallList, withWalls, n, threads, blockStart, speed.data(), &blockCost);
      splitOfList = list.version;
      splitOfRows = n;
      sweepTime.assign(static_cast<std::size_t>(threads), SweepTimes{});
      sweepsTimed = 0;
    }
    if (threads > 1 && (list.version != receiversOfList || blockStart != receiversOfBlocks || receives.size() != n))
      findReceivers(list, n, threads);
    outgoing.resize(static_cast<std::size_t>(threads));
    deferred.resize(static_cast<std::size_t>(threads));
    for (int t = 0; t < threads; ++t) {
      outgoing[t].clear();
      deferred[t].clear();
    }
  }
  /// Thread t swept its block in `seconds`.
  void recordSweep(int t, double seconds) {
    SweepTimes& s = sweepTime[t];
    if (s.count < static_cast<int>(s.seconds.size())) s.seconds[s.count] = seconds;
    ++s.count;
  }
};

}  // namespace gf::dem
