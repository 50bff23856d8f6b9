#pragma once
// Linked cells + Verlet lists with a skin (Allen & Tildesley, Computer Simulation of Liquids,
// sec. 5.3). Half list in compressed rows: row i holds partners j > i (ascending) with
// |x_i - x_j| < r_i + r_j + skin. Each entry carries its contact history, which is carried over
// on every rebuild, also when particles were reordered, removed or inserted in between.
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/serialize.hpp"
#include "dem/particles.hpp"
#include "dem/periodic_box.hpp"

namespace gf::dem {

class NeighbourList {
 public:
  std::vector<std::uint32_t> rowStart;  // size n + 1
  std::vector<std::uint32_t> partner;   // j > i
  std::vector<Vec3> tangentialHistory;  // per entry, i's view
  std::vector<Vec3> rollingHistory;     // per entry (EPSD only, else empty)
  /// Touching pairs of rows [0, i) at the positions of the last build (size n + 1; derived, not
  /// saved: counted by build() and, after load(), by countTouching(); empty on one thread). The
  /// force loop splits its rows among threads by the work this predicts (BlockSplit).
  std::vector<std::uint32_t> touchingStart;
  /// Incremented by every build() and load(): who keeps data derived from the list knows when to
  /// derive it again.
  std::uint64_t version = 0;

  /// Rebuilds the list for `p`. `previousIndex[k]` is the index particle k had at the previous
  /// build (-1 for new particles); histories of pairs that persist are copied (sign flipped when
  /// the pair's row owner changed).
  void build(const ParticleSet& p, const PeriodicBox& box, const Vec3& boxMin, const Vec3& boxMax, double skin,
             const std::vector<std::int64_t>& previousIndex, bool withRollingHistory);

  std::size_t rows() const { return rowStart.empty() ? 0 : rowStart.size() - 1; }
  std::size_t entries() const { return partner.size(); }
  std::size_t memoryBytes() const;

  /// Fills touchingStart from the positions and radii the list was built with (a pure function of
  /// them: a restart, which restores those positions, gets the same counts).
  void countTouching(const std::vector<Vec3>& positionAtBuild, const std::vector<double>& radius,
                     const PeriodicBox& box);

  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);

 private:
  std::vector<std::vector<std::uint32_t>> scratch_;  // chunk buffers of build()
};

/// Compressed rows in one pass over the rows (no separate count pass): the rows are cut into
/// chunks, each of which appends its rows' entries to its own buffer (`rowEntries(i, buffer)`
/// appends row i's entries and may reorder them in place); the row starts follow from the counts,
/// `allocate(total)` sizes the caller's per-entry arrays (once, on the master thread), and the
/// chunks are copied into place, `finishRow(i)` called for each of their rows. The result does
/// not depend on the thread count or on the chunking. `scratch` keeps the chunk buffers between
/// builds.
///
/// Thread t takes the same contiguous chunks in both passes and in every build (static schedule),
/// so a row range, its buffers and its output stay in one core's cache: a cache line moving
/// between two cores costs some hundred nanoseconds, and dynamic chunks made each thread as slow
/// on its half of the settled bed's list build as one thread on all of it. The cost of a row varies
/// along the array (the dense and the dilute parts of a bed lie in different halves of a Morton
/// order), so with `costStart` (cumulative estimated cost of rows [0, i), size n + 1: e.g. the
/// previous build's row starts) the chunks hold equal shares of 1 per row + costStart; without it
/// equal numbers of rows. The master allocates, so that the arrays come from its malloc arena
/// every time (allocating on whichever thread arrived first cost 0.6-0.9 ms per build on 2
/// threads in page faults, against 0.05 ms).
template <class T, class RowEntries, class Allocate, class FinishRow>
void buildCompressedRows(std::size_t n, std::vector<std::vector<T>>& scratch, std::vector<std::uint32_t>& rowStart,
                         std::vector<T>& entries, RowEntries&& rowEntries, Allocate&& allocate, FinishRow&& finishRow,
                         const std::uint32_t* costStart = nullptr) {
  const int threads = static_cast<std::int64_t>(n) >= 512 ? omp_get_max_threads() : 1;  // kMinParallelLoop
  const std::int64_t chunks = threads > 1 ? 8 * threads : 1;
  if (static_cast<std::int64_t>(scratch.size()) < chunks) scratch.resize(chunks);
  // Chunk c: rows [bound[c], bound[c + 1]); equal shares of rows + costStart (before rowStart is
  // overwritten: costStart may be the caller's previous rowStart).
  std::vector<std::size_t> bound(static_cast<std::size_t>(chunks) + 1, n);
  const auto share = [&](std::size_t i) {
    return static_cast<double>(i) + (costStart ? static_cast<double>(costStart[i]) : 0.0);
  };
  for (std::int64_t c = 0; c < chunks; ++c) {
    const double target = share(n) * static_cast<double>(c) / static_cast<double>(chunks);
    std::size_t lo = c == 0 ? 0 : bound[c - 1], hi = n;  // first row whose share reaches target
    while (lo < hi) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (share(mid) >= target) hi = mid;
      else lo = mid + 1;
    }
    bound[c] = lo;
  }
  rowStart.assign(n + 1, 0);
  auto chunkBegin = [&](std::int64_t c) { return bound[static_cast<std::size_t>(c)]; };
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < chunks; ++c) {
      std::vector<T>& buffer = scratch[c];
      buffer.clear();
      for (std::size_t i = chunkBegin(c); i < chunkBegin(c + 1); ++i) {
        const std::size_t before = buffer.size();
        rowEntries(i, buffer);
        rowStart[i + 1] = static_cast<std::uint32_t>(buffer.size() - before);
      }
    }  // implicit barrier
#pragma omp masked
    {
      for (std::size_t i = 0; i < n; ++i) rowStart[i + 1] += rowStart[i];
      entries.resize(rowStart[n]);
      allocate(static_cast<std::size_t>(rowStart[n]));
    }
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < chunks; ++c) {
      const std::vector<T>& buffer = scratch[c];
      const std::size_t begin = chunkBegin(c), end = chunkBegin(c + 1);
      std::copy(buffer.begin(), buffer.end(), entries.begin() + rowStart[begin]);
      for (std::size_t i = begin; i < end; ++i) finishRow(i);
    }
  }
}

/// Whether the list build may test its candidates with AVX-512 (default true; a no-op on CPUs
/// without AVX-512F/VL). The same lists bit for bit either way; tests switch it off to check the
/// generic form too. Not thread-safe: set it between builds.
void allowNeighbourAvx512(bool allowed);

/// Linked-cell binning of particle indices (counting sort, deterministic).
struct CellGrid {
  int dims[3] = {1, 1, 1};
  /// Cells along x are 1/xSplit of the interaction range wide (x is the axis along which cells are
  /// consecutive in the cell order): the candidates of a (y, z) row of cells are still one range,
  /// now xSplit cells either side, which covers 2 + 1/xSplit instead of 3 ranges along x
  /// (-22 % candidates for xSplit = 3).
  int xSplit = 1;
  Vec3 origin;
  Vec3 width;  // cell width per axis, m
  std::vector<std::uint32_t> cellStart;  // size cells + 1
  std::vector<std::uint32_t> sorted;     // particle indices by cell, ascending within a cell
  std::vector<std::uint32_t> cellOf;     // per particle
  std::vector<std::array<int, 3>> coordOf;  // per particle: its cell's (x, y, z) (no divisions to recover them)

  void build(const std::vector<Vec3>& x, const Vec3& boxMin, const Vec3& boxMax, double minCellSize);
  int cellIndex(const Vec3& x, int c[3]) const;
};

/// Morton (Z-order) code of the cell of cellSize (counted from boxMin) that holds x.
std::uint64_t mortonCode(const Vec3& x, const Vec3& boxMin, double cellSize);
/// Indices sorted by key, ties in index order (stable radix sort).
std::vector<std::uint32_t> orderByKey(const std::vector<std::uint64_t>& key);
/// Sorts `subset` (indices into p) by (orderKey, id), the order of the particle arrays
/// (ParticleSet::orderKey): a radix sort by key, then runs of equal keys by id; no work when sorted.
void sortByKeyThenId(std::vector<std::uint32_t>& subset, const ParticleSet& p);
/// Order of particles along a Morton (Z-order) curve of their cells, ties by index.
std::vector<std::uint32_t> mortonOrder(const std::vector<Vec3>& x, const Vec3& boxMin, const Vec3& boxMax,
                                       double cellSize);

}  // namespace gf::dem
