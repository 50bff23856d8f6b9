#pragma once
// Linked cells + Verlet lists with a skin (Allen & Tildesley, Computer Simulation of Liquids,
// sec. 5.3). Half list in compressed rows: row i holds partners j > i (ascending) with
// |x_i - x_j| < r_i + r_j + skin. Each entry carries its contact history, which is carried over
// on every rebuild, also when particles were reordered, removed or inserted in between.
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

  /// Rebuilds the list for `p`. `previousIndex[k]` is the index particle k had at the previous
  /// build (-1 for new particles); histories of pairs that persist are copied (sign flipped when
  /// the pair's row owner changed).
  void build(const ParticleSet& p, const PeriodicBox& box, const Vec3& boxMin, const Vec3& boxMax, double skin,
             const std::vector<std::int64_t>& previousIndex, bool withRollingHistory);

  std::size_t rows() const { return rowStart.empty() ? 0 : rowStart.size() - 1; }
  std::size_t entries() const { return partner.size(); }
  std::size_t memoryBytes() const;

  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);
};

/// Linked-cell binning of particle indices (counting sort, deterministic).
struct CellGrid {
  int dims[3] = {1, 1, 1};
  Vec3 origin;
  Vec3 width;  // cell width per axis, m
  std::vector<std::uint32_t> cellStart;  // size cells + 1
  std::vector<std::uint32_t> sorted;     // particle indices by cell, ascending within a cell
  std::vector<std::uint32_t> cellOf;     // per particle

  void build(const std::vector<Vec3>& x, const Vec3& boxMin, const Vec3& boxMax, double minCellSize);
  int cellIndex(const Vec3& x, int c[3]) const;
};

/// Order of particles along a Morton (Z-order) curve of their cells, ties by index.
std::vector<std::uint32_t> mortonOrder(const std::vector<Vec3>& x, const Vec3& boxMin, const Vec3& boxMax,
                                       double cellSize);

}  // namespace gf::dem
