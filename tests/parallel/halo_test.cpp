// Ghost exchange of grid fields between ranks (parallel/halo.hpp). Under mpirun (ctest runs these
// with -n 2 and -n 4) each rank holds its box of a global grid: after fillGhosts every ghost across
// a Shared side (faces, edges, corners, periodic wrap between ranks) holds the global field's value
// there, for cell and face (MAC) staggering; sumGhosts moves every ghost deposit to its owner and
// keeps the global total exactly (integer-valued deposits: sums without rounding). On one process
// the verbs touch nothing.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "parallel/decomposition.hpp"
#include "parallel/environment.hpp"
#include "parallel/halo.hpp"

namespace gf::parallel {
namespace {

constexpr std::array<int, 3> kCells{12, 7, 6};  // an uneven split along y; >= 3 cells per rank

/// A value coding the global point index (wrapped on periodic axes); distinct per point.
double code(std::array<int, 3> g) { return 1.0 + g[0] + 100.0 * g[1] + 10000.0 * g[2]; }

/// A global point index wrapped on the periodic axes (a periodic face field's last face is its first).
std::array<int, 3> wrap(std::array<int, 3> g, const std::array<bool, 3>& periodic) {
  for (int a = 0; a < 3; ++a)
    if (periodic[a]) g[a] = ((g[a] % kCells[a]) + kCells[a]) % kCells[a];
  return g;
}

Domain domainWith(std::array<bool, 3> periodic) {
  Domain d;
  d.min = Vec3{0.0, 0.0, 0.0};
  d.max = Vec3{1.2, 0.7, 0.6};
  d.periodic = periodic;
  return d;
}

CartesianGrid localGrid(const Decomposition& d) {
  CartesianGrid g;
  g.ghosts = 2;
  g.cells = d.cellCount();
  g.spacing = Vec3{0.1, 0.1, 0.1};
  for (int a = 0; a < 3; ++a) g.origin[a] = d.domain().min[a] + d.cellOffset()[a] * 0.1;
  return g;
}

/// Layouts that exist for the rank count of this run.
std::vector<Layout> layoutsFor(int ranks) {
  if (ranks == 1) return {{1, 1, 1}};
  if (ranks == 2) return {{2, 1, 1}, {1, 2, 1}, {1, 1, 2}};
  if (ranks == 4) return {{2, 2, 1}, {1, 2, 2}, {2, 1, 2}, {4, 1, 1}};
  return {{ranks, 1, 1}};
}

const std::vector<std::array<bool, 3>> kPeriodicity{
    {false, false, false}, {true, false, false}, {true, true, true}, {false, true, true}};

TEST(Halo, FillReproducesTheGlobalFieldInEveryExchangedGhost) {
  const Environment& env = Environment::instance();
  for (const Layout& layout : layoutsFor(env.size()))
    for (const auto& periodic : kPeriodicity) {
      const Decomposition d(domainWith(periodic), layout, env.size(), env.rank(), kCells);
      const CartesianGrid grid = localGrid(d);
      for (int st = 0; st < 4; ++st) {
        const auto staggering = static_cast<Staggering>(st);
        Field f(grid, staggering, -1.0);
        const auto& pts = f.points();
        const auto off = d.cellOffset();
        // Owned points: the interior, less face n across a Shared upper side (the upper rank's face 0).
        for (int k = 0; k < pts[2]; ++k)
          for (int j = 0; j < pts[1]; ++j)
            for (int i = 0; i < pts[0]; ++i) f(i, j, k) = code(wrap({off[0] + i, off[1] + j, off[2] + k}, periodic));
        for (int a = 0; a < 3; ++a)
          if (st == a + 1 && d.side(a, +1) == Side::Shared)
            for (int k = 0; k < pts[2]; ++k)
              for (int j = 0; j < pts[1]; ++j)
                for (int i = 0; i < pts[0]; ++i)
                  if ((a == 0 ? i : (a == 1 ? j : k)) == pts[a] - 1) f(i, j, k) = -2.0;
        fillGhosts(f, d);
        const int g = grid.ghosts;
        int checked = 0;
        for (int k = -g; k < pts[2] + g; ++k)
          for (int j = -g; j < pts[1] + g; ++j)
            for (int i = -g; i < pts[0] + g; ++i) {
              const std::array<int, 3> local{i, j, k};
              std::array<int, 3> global{};
              bool exchanged = false, defined = true;
              for (int a = 0; a < 3; ++a) {
                const int own = pts[a] - (st == a + 1 && d.side(a, +1) == Side::Shared ? 1 : 0);
                const bool low = local[a] < 0, high = local[a] >= own;
                if ((low && d.side(a, -1) == Side::Shared) || (high && d.side(a, +1) == Side::Shared)) exchanged = true;
                else if (local[a] < 0 || local[a] >= pts[a]) defined = false;  // a ghost left to the boundary code
                global[a] = off[a] + local[a];
              }
              global = wrap(global, periodic);
              if (!exchanged || !defined) continue;
              ++checked;
              ASSERT_EQ(f(i, j, k), code(global))
                  << "rank " << d.rank() << " layout " << d.describe() << " periodic " << periodic[0] << periodic[1]
                  << periodic[2] << " staggering " << st << " point " << i << " " << j << " " << k;
            }
        if (env.size() > 1 && (d.side(0, 1) == Side::Shared || d.side(1, 1) == Side::Shared || d.side(2, 1) == Side::Shared)) {
          EXPECT_GT(checked, 0);
        }
      }
    }
}

TEST(Halo, SumMovesEveryDepositToItsOwnerAndKeepsTheTotal) {
  const Environment& env = Environment::instance();
  for (const Layout& layout : layoutsFor(env.size()))
    for (const auto& periodic : kPeriodicity) {
      const Decomposition d(domainWith(periodic), layout, env.size(), env.rank(), kCells);
      const CartesianGrid grid = localGrid(d);
      for (int st = 0; st < 4; ++st) {
        Field f(grid, static_cast<Staggering>(st));
        const auto& pts = f.points();
        const int g = grid.ghosts;
        // Integer deposits everywhere, ghosts included: exact sums in any order.
        double before = 0.0;
        for (int k = -g; k < pts[2] + g; ++k)
          for (int j = -g; j < pts[1] + g; ++j)
            for (int i = -g; i < pts[0] + g; ++i) {
              const double v = 1.0 + ((i + 3 * j + 7 * k + 11 * env.rank()) & 15);
              f(i, j, k) = v;
              before += v;
            }
        const double totalBefore = env.sum(before);
        sumGhosts(f, d);
        double after = 0.0;
        for (double v : f.data()) after += v;
        EXPECT_EQ(env.sum(after), totalBefore) << "layout " << d.describe() << " staggering " << st;
        // Every ghost across a Shared side was zeroed.
        for (int k = -g; k < pts[2] + g; ++k)
          for (int j = -g; j < pts[1] + g; ++j)
            for (int i = -g; i < pts[0] + g; ++i) {
              const std::array<int, 3> local{i, j, k};
              bool shared = false;
              for (int a = 0; a < 3; ++a) {
                const int own = pts[a] - (st == a + 1 && d.side(a, +1) == Side::Shared ? 1 : 0);
                if ((local[a] < 0 && d.side(a, -1) == Side::Shared) || (local[a] >= own && d.side(a, +1) == Side::Shared))
                  shared = true;
              }
              if (shared) {
                ASSERT_EQ(f(i, j, k), 0.0) << "point " << i << " " << j << " " << k;
              }
            }
      }
    }
}

TEST(Halo, SumOfADepositInACornerGhostReachesTheDiagonalOwner) {
  // One unit deposited by every rank in its upper corner ghost (across Shared sides) lands at the
  // owner's matching point: the sum of fills equals the number of ranks whose corner maps there.
  const Environment& env = Environment::instance();
  for (const Layout& layout : layoutsFor(env.size())) {
    const Decomposition d(domainWith({true, true, true}), layout, env.size(), env.rank(), kCells);
    Field f(localGrid(d));
    const auto& pts = f.points();
    f(pts[0], pts[1], pts[2]) += 1.0;  // the first ghost beyond the upper corner
    sumGhosts(f, d);
    // On every axis the upper side is Shared (several ranks) or Periodic (one): a Periodic axis
    // keeps the deposit in this rank's ghost (the boundary code folds it), a Shared one sends it.
    std::array<int, 3> at{};
    for (int a = 0; a < 3; ++a) at[a] = d.side(a, +1) == Side::Shared ? 0 : pts[a];
    // The owner received from the rank below it along every Shared axis: its own point `at`.
    EXPECT_EQ(f(at[0], at[1], at[2]), 1.0) << "layout " << d.describe();
    double total = 0.0;
    for (double v : f.data()) total += v;
    EXPECT_EQ(env.sum(total), env.size());
  }
}

TEST(Halo, GatherAssemblesTheWholeGridAndExtractGivesEachBoxBack) {
  // Each rank's points coded by their global index: rank 0 gets the whole grid's field with every
  // point of the domain (and the wrap-around points of periodic axes) coded; a rank's box taken
  // from it is the rank's field with its ghosts filled.
  const Environment& env = Environment::instance();
  for (const Layout& layout : layoutsFor(env.size()))
    for (const auto& periodic : kPeriodicity) {
      const Decomposition d(domainWith(periodic), layout, env.size(), env.rank(), kCells);
      const CartesianGrid grid = localGrid(d);
      CartesianGrid wholeGrid = grid;
      wholeGrid.cells = kCells;
      wholeGrid.origin = d.domain().min;
      for (int st = 0; st < 4; ++st) {
        Field f(grid, static_cast<Staggering>(st));
        const auto& pts = f.points();
        const auto off = d.cellOffset();
        for (int k = 0; k < pts[2]; ++k)
          for (int j = 0; j < pts[1]; ++j)
            for (int i = 0; i < pts[0]; ++i) f(i, j, k) = code(wrap({off[0] + i, off[1] + j, off[2] + k}, periodic));
        fillGhosts(f, d);
        Field whole;
        gatherField(f, d, wholeGrid, whole);
        if (d.rank() == 0) {
          const auto& wp = whole.points();
          for (int k = 0; k < wp[2]; ++k)
            for (int j = 0; j < wp[1]; ++j)
              for (int i = 0; i < wp[0]; ++i) {
                ASSERT_EQ(whole(i, j, k), code(wrap({i, j, k}, periodic))) << "layout " << d.describe() << " st " << st;
              }
          // Wrap-around points of a periodic axis split among ranks: the other end (one rank's
          // periodic ghosts are its boundary code's, not filled in this test).
          for (int a = 0; a < 3; ++a)
            if (periodic[a] && layout[a] > 1) {
              std::array<int, 3> at{1, 1, 1}, inside{1, 1, 1};
              at[a] = -1;
              inside[a] = kCells[a] - 1;
              EXPECT_EQ(whole(at[0], at[1], at[2]), whole(inside[0], inside[1], inside[2]));
            }
        }
        // Every rank: its box back from the whole grid (broadcast here through a second gather's
        // data: rank 0's whole grid, rebuilt on the others from the codes).
        Field all(wholeGrid, static_cast<Staggering>(st));
        const int g = grid.ghosts;
        const auto& ap = all.points();
        for (int k = -g; k < ap[2] + g; ++k)
          for (int j = -g; j < ap[1] + g; ++j)
            for (int i = -g; i < ap[0] + g; ++i) all(i, j, k) = code(wrap({i, j, k}, periodic));
        Field back(grid, static_cast<Staggering>(st));
        extractBox(all, d, back);
        for (int k = -g; k < pts[2] + g; ++k)
          for (int j = -g; j < pts[1] + g; ++j)
            for (int i = -g; i < pts[0] + g; ++i) {
              ASSERT_EQ(back(i, j, k), all(off[0] + i, off[1] + j, off[2] + k));
            }
      }
    }
}

TEST(Halo, RejectsABoxThinnerThanTheGhostLayers) {
  const Environment& env = Environment::instance();
  if (env.size() < 2) GTEST_SKIP() << "needs several ranks";
  const std::array<int, 3> cells{2 * env.size(), 4, 4};
  const Decomposition d(domainWith({false, false, false}), {env.size(), 1, 1}, env.size(), env.rank(), cells);
  CartesianGrid grid;
  grid.cells = d.cellCount();  // 2 cells per rank: enough for cells, not for the x faces
  Field cell(grid), face(grid, Staggering::FaceX);
  EXPECT_NO_THROW(fillGhosts(cell, d));
  EXPECT_THROW(fillGhosts(face, d), std::invalid_argument);
}

}  // namespace
}  // namespace gf::parallel
