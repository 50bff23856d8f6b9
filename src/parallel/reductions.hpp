#pragma once
// The allreduces behind core/reduction.hpp's sumAcrossRanks and maxAcrossRanks. A solver whose grid
// is split among the ranks of a Decomposition opens a RankReductionScope around its work (a step,
// a time-step estimate): inside it, every dot product, norm and partial sum of core/reduction.hpp
// combines the ranks' local values with MPI_Allreduce on the run's communicator. Outside any scope,
// or for a decomposition of one rank, the combinations stay the identity (the single-process bits;
// a solver that owns its whole grid in a run of several ranks keeps its own, replicated, results).
// Scopes nest; the previous combination is restored on exit.
#include "core/reduction.hpp"
#include "parallel/decomposition.hpp"

namespace gf::parallel {

class RankReductionScope {
 public:
  explicit RankReductionScope(const Decomposition& d);
  ~RankReductionScope();
  RankReductionScope(const RankReductionScope&) = delete;
  RankReductionScope& operator=(const RankReductionScope&) = delete;

 private:
  const RankReductions* previous_;
  bool installed_ = false;
};

/// The opposite: inside it, the reductions are this rank's own again (a solver that one rank runs
/// for all, e.g. the gathered pressure solve, inside a step whose scope combines the ranks).
class ThisRankOnlyScope {
 public:
  ThisRankOnlyScope() : previous_(rankReductions()) { setRankReductions(nullptr); }
  ~ThisRankOnlyScope() { setRankReductions(previous_); }
  ThisRankOnlyScope(const ThisRankOnlyScope&) = delete;
  ThisRankOnlyScope& operator=(const ThisRankOnlyScope&) = delete;

 private:
  const RankReductions* previous_;
};

/// The allreduces themselves (MPI_SUM, MPI_MAX over all ranks of the run).
const RankReductions& allRankReductions();

}  // namespace gf::parallel
