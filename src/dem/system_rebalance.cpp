// Load balancing of the DEM across MPI ranks (BalanceSettings, case section `parallel`).
//
// At the first list build on or after every parallel.rebalance_interval steps, the ranks add up the
// loads of the particles each would own at this build (their centres in its box): 1 per particle,
// or with parallel.rebalance_weight: pairs 1 + the particle's pairs in the last neighbour list.
// When max/mean exceeds parallel.rebalance_threshold, a recursive coordinate bisection of all owned
// particles with these weights (parallel::bisect, Zoltan RCB) gives new boxes, one per rank, and
// the migration of the same build sends every particle to the rank whose new box holds it (any
// rank, not only a former neighbour), with its contact histories. Only list builds rebalance, and the ones a run on one
// rank makes too, so the arrays keep their one global order (orderKey, id) and the results their
// bits. Every decision is collective: global counts, rank 0's boxes.
//
// New boxes are refused (the layout stays, with a notice) when they would be narrower than the
// ghosts' reach (largest diameter + skin) along a split axis, or would not lower the imbalance.
// Cases with a fluid keep the Cartesian layout of their grid (the fluid solver works on it).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <stdexcept>

#include "dem/system.hpp"
#include "parallel/rebalance.hpp"

namespace gf::dem {

bool System::rebalanceIfDue(const std::vector<std::uint32_t>& order, double reach) {
  if (!distributed_ || balance_.interval <= 0) return false;
  const long long due = steps_ / balance_.interval;
  if (due <= balanceChecks_) return false;
  balanceChecks_ = due;
  const bool root = decomposition_.rank() == 0;
  // A case with a fluid: its boxes are the grid's, re-cut with the cells (Simulation::rebalanceIfDue).
  if (decomposition_.gridded()) return false;
  // A case layout narrower than the reach is refused after the first build (checkBoxesHoldTheReach).
  if (!decomposition_.explicitBoxes() && decomposition_.smallestBoxWidth() < reach) return false;
  // The particles this rank owns at this build (ghosts are sent again after the migration).
  // Their loads: 1 each, or 1 + the pairs of the last list build they take part in (rows and
  // partners; a particle inserted since then: 1).
  const ParticleSet& p = particles_;
  std::vector<long long> pairs;
  if (balance_.byPairs) {
    pairs.assign(list_.rows(), 0);
    for (std::size_t r = 0; r < list_.rows(); ++r) {
      pairs[r] += list_.rowStart[r + 1] - list_.rowStart[r];
      for (std::uint32_t k = list_.rowStart[r]; k < list_.rowStart[r + 1]; ++k) ++pairs[list_.partner[k]];
    }
  }
  std::vector<std::int64_t> ids;
  std::vector<Vec3> positions;
  std::vector<long long> weight;
  for (std::uint32_t i : order)
    if (!p.isGhost(i)) {
      ids.push_back(p.id[i]);
      positions.push_back(p.position[i]);
      weight.push_back(1 + (i < pairs.size() ? pairs[i] : 0));
    }
  const int ranks = decomposition_.ranks();
  auto loads = [](const std::vector<long long>& counts) {
    return std::vector<double>(counts.begin(), counts.begin() + static_cast<std::ptrdiff_t>(counts.size() - 1));
  };
  std::vector<long long> counts(static_cast<std::size_t>(ranks) + 1, 0);  // (last: the particles)
  for (std::size_t k = 0; k < positions.size(); ++k) {
    counts[static_cast<std::size_t>(decomposition_.ownerOf(positions[k]))] += weight[k];
    ++counts.back();
  }
  counts = parallel::sumOverRanks(counts);
  const double before = parallel::imbalance(loads(counts));
  if (before <= balance_.threshold) return false;

  const std::vector<parallel::Box> boxes =
      parallel::bisect(domain_, ids, positions, std::vector<double>(weight.begin(), weight.end()), ranks);
  auto notice = [&](const std::string& why) {
    if (root) spdlog::info("parallel: imbalance {:.3f} at step {}, boxes kept: {}", before, steps_, why);
  };
  parallel::Decomposition next;
  try {
    next = parallel::Decomposition(domain_, boxes, decomposition_.rank(), reach);
  } catch (const std::invalid_argument& e) {
    notice(e.what());
    return false;
  }
  // Boxes at least as wide as the reach (as checkBoxesHoldTheReach asks of the case's layout).
  if (next.smallestBoxWidth() < reach) {
    notice(fmt::format("the bisection makes a box {:.4g} m wide, narrower than the contact reach {:.4g} m",
                       next.smallestBoxWidth(), reach));
    return false;
  }
  std::vector<long long> after(static_cast<std::size_t>(ranks) + 1, 0);  // (last: particles moved)
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const int owner = next.ownerOf(positions[k]);
    after[static_cast<std::size_t>(owner)] += weight[k];
    if (owner != decomposition_.ownerOf(positions[k])) ++after.back();
  }
  after = parallel::sumOverRanks(after);
  const double balanced = parallel::imbalance(loads(after));
  if (balanced >= before) {
    notice(fmt::format("the bisection gives {:.3f}", balanced));
    return false;
  }
  const long long total = counts.back();
  if (root)
    spdlog::info("parallel: rebalanced at step {}: imbalance (max/mean {} per rank) {:.3f} -> {:.3f}, {} of {} "
                 "particles ({:.1f} %) move to another rank",
                 steps_, balance_.byPairs ? "particles + pairs" : "particles", before, balanced, after.back(), total,
                 total > 0 ? 100.0 * static_cast<double>(after.back()) / static_cast<double>(total) : 0.0);
  decomposition_ = std::move(next);
  return true;
}

}  // namespace gf::dem
