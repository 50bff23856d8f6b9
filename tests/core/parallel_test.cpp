#include <gtest/gtest.h>

#include <omp.h>

#include <vector>

#include "core/parallel.hpp"

namespace {
// Every member writes its slot, waits, then reads every slot: with a working barrier it sees this
// round's values of all members, never a neighbour's last round (a missing release or a member
// let through early shows as a mismatch). The second wait keeps the next round's writes from
// overtaking the reads. Teams of 2 and 3 on a 2-core machine: the second also takes the sleeping
// path (more members than cores).
int mismatchesOverRounds(int team, int rounds) {
  gf::TeamBarrier barrier(team);
  std::vector<long> slot(static_cast<std::size_t>(team), -1);
  int mismatches = 0;
#pragma omp parallel num_threads(team) reduction(+ : mismatches)
  {
    const int t = omp_get_thread_num();
    const int members = omp_get_num_threads();
    for (int r = 0; r < rounds; ++r) {
      slot[static_cast<std::size_t>(t)] = static_cast<long>(r) * members + t;
      barrier.wait();
      for (int m = 0; m < members; ++m)
        if (slot[static_cast<std::size_t>(m)] != static_cast<long>(r) * members + m) ++mismatches;
      barrier.wait();
    }
  }
  return mismatches;
}
}  // namespace

TEST(TeamBarrier, EveryMemberSeesTheRoundsWritesOfAllMembers) {
  EXPECT_EQ(mismatchesOverRounds(2, 20000), 0);
  EXPECT_EQ(mismatchesOverRounds(3, 2000), 0);
}

TEST(TeamBarrier, ATeamOfOneDoesNotWait) {
  gf::TeamBarrier barrier(1);
  for (int r = 0; r < 10; ++r) barrier.wait();  // (would hang if it waited for a second member)
  SUCCEED();
}
