// Divided / satellite-point scheme (CFDEM 'divided', dividedVoidFraction; seed 001 "SPM"):
// the volume is split into 29 equal parts at the centre and at 28 satellite points, 14 on each of
// two spheres of radius 0.623926 r and 0.917902 r (0.623926 + 0.293976): 8 points at polar angles
// pi/4, 3pi/4 and azimuths pi/4 + k pi/2, and 6 on the coordinate axes. Each part goes to the cell
// containing its point (wrapped at periodic boundaries, folded back at walls). The coordinates
// +-r_s/2 and +-r_s/sqrt(2) are written exactly symmetric. Particles smaller than a cell (the
// common case) take a fast path: 2 x 2 x 2 cells, point counts from a table (see addBlock).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>
#include "core/cpu_features.hpp"
#if defined(GF_X86_SIMD)
#include <immintrin.h>
#endif

#include "coupling/axis_offsets.hpp"
#include "coupling/void_fraction/divided.hpp"
#include "coupling/void_fraction/void_fraction_scheme.hpp"
#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

constexpr int kPoints = 29;

std::array<Vec3, kPoints> unitSatellitePoints() {
  // sin(pi/4) cos(pi/4 + k pi/2) = +-1/2 and cos(pi/4), cos(3 pi/4) = +-sqrt(1/2), written
  // exactly symmetric (the trigonometric values differ from them in the last bits), so that each
  // axis has 9 distinct coordinates
  std::array<Vec3, kPoints> pts{};
  int n = 0;
  pts[n++] = {0.0, 0.0, 0.0};
  const double halfRoot2 = std::sqrt(0.5);
  for (double r : {0.623926, 0.623926 + 0.293976}) {
    for (int a = 0; a < 4; ++a) {
      const double sx = (a == 0 || a == 3) ? 1.0 : -1.0, sy = a < 2 ? 1.0 : -1.0;  // azimuth pi/4 + a pi/2
      for (double sz : {1.0, -1.0}) pts[n++] = {sx * 0.5 * r, sy * 0.5 * r, sz * halfRoot2 * r};
    }
    for (int axis = 0; axis < 3; ++axis)
      for (double s : {-1.0, 1.0}) {
        Vec3 v{};
        v[axis] = s * r;
        pts[n++] = v;
      }
  }
  return pts;
}

constexpr int kValues = 9;  // distinct coordinates per axis

/// The unit points per axis as 9 sorted distinct coordinates, and for every split of each axis
/// (the first s_a coordinates in the lower cell, the rest in the upper) the number of points in
/// each of the 8 cells of the 2 x 2 x 2 block: count[s_x][s_y][s_z][bit0 x + bit1 y + bit2 z].
struct UnitPoints {
  double c[3][kPoints];
  double value[3][kValues];
  std::uint8_t count[kValues + 1][kValues + 1][kValues + 1][8] = {};
  std::uint64_t packedCount[kValues + 1][kValues + 1][kValues + 1];  // the 8 counts, byte b = count[b]
  double reach = 0.0;  // largest |coordinate|
  UnitPoints() {
    const auto pts = unitSatellitePoints();
    int index[3][kPoints];
    for (int a = 0; a < 3; ++a) {
      std::array<double, kPoints> v;
      for (int m = 0; m < kPoints; ++m) v[m] = c[a][m] = pts[m][a];
      std::sort(v.begin(), v.end());
      const auto end = std::unique(v.begin(), v.end());
      if (end - v.begin() != kValues) throw std::logic_error("divided: unit points must have 9 coordinates per axis");
      std::copy(v.begin(), end, value[a]);
      for (int m = 0; m < kPoints; ++m) index[a][m] = static_cast<int>(std::find(v.begin(), end, c[a][m]) - v.begin());
      reach = std::max(reach, -value[a][0]);
    }
    for (int sx = 0; sx <= kValues; ++sx)
      for (int sy = 0; sy <= kValues; ++sy)
        for (int sz = 0; sz <= kValues; ++sz)
          for (int m = 0; m < kPoints; ++m) {
            const int b = (index[0][m] >= sx ? 1 : 0) | (index[1][m] >= sy ? 2 : 0) | (index[2][m] >= sz ? 4 : 0);
            ++count[sx][sy][sz][b];
          }
    for (int sx = 0; sx <= kValues; ++sx)
      for (int sy = 0; sy <= kValues; ++sy)
        for (int sz = 0; sz <= kValues; ++sz) {
          std::uint64_t packed = 0;
          for (int b = 0; b < 8; ++b) packed |= static_cast<std::uint64_t>(count[sx][sy][sz][b]) << (8 * b);
          packedCount[sx][sy][sz] = packed;
        }
  }
};

const UnitPoints unit;  // built at start-up, read-only afterwards

#if defined(__GNUC__)
using Double2 = double __attribute__((vector_size(16)));
using Mask2 = long long __attribute__((vector_size(16)));
#endif

/// The unit coordinates scaled by a radius, r u_v, per axis (the same products as r * u_v
/// computed per point; reused while consecutive particles share the radius).
struct ScaledPoints {
  bool valid = false;
  double r = 0.0;
  double value[3][kValues] = {};
  bool scaledFor(double radius) const { return valid && radius == r; }
  void scale(double radius) {
    valid = true;
    r = radius;
    for (int a = 0; a < 3; ++a)
      for (int v = 0; v < kValues; ++v) value[a][v] = radius * unit.value[a][v];
  }
};

/// Along one axis: the cell lo of the lowest point, and the number of points (of the 9 sorted
/// unit coordinates) in cell lo; the others lie in lo + 1 (block path, points span < 1 cell).
/// The scaled coordinate of point v is (x + r u_v - origin) / h exactly as cellOf computes it;
/// it grows monotonically with u (rounding is monotone), so the points in the lower cell are the
/// first `split` sorted coordinates. ru: the r u_v of the axis.
struct AxisSplit {
  int lo;
  int split;
};
inline AxisSplit splitAxis(double x, const double (&ru)[kValues], double origin, double inv) {
  const int lo = floorToInt((x + ru[0] - origin) * inv);
  const double upper = lo + 1.0;
#if defined(__GNUC__)
  // the 8 upper coordinates two at a time (same operations, same rounding as the scalar form)
  Mask2 below{0, 0};
  for (int v = 1; v < kValues; v += 2) {
    const Double2 u{ru[v], ru[v + 1]};
    below += (x + u - origin) * inv < upper;  // -1 where true
  }
  return {lo, static_cast<int>(1 - below[0] - below[1])};
#else
  int s = 1;  // the lowest coordinate lies below lo + 1 by the definition of lo
  for (int v = 1; v < kValues; ++v) s += (x + ru[v] - origin) * inv < upper ? 1 : 0;
  return {lo, s};
#endif
}

using AxisOffsets = AxisOffsetTable<std::size_t>;

VectorForm blockPathAvx512(InstructionSet::Avx512fAvx2);  // addBlocksAvx512

class DividedVoidFraction final : public VoidFractionScheme {
 public:
  explicit DividedVoidFraction(Params&) {}
  void buildStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    if (!beginStencils(particles, topology, stencils)) return;  // built by beginStencils
    constexpr std::int64_t kPiece = 256;
    const auto n = static_cast<std::int64_t>(particles.size());
    forEachIndex((n + kPiece - 1) / kPiece, 29 * kPiece, [&](std::int64_t piece) {
      const auto begin = static_cast<std::size_t>(piece * kPiece);
      buildStencilRange(particles, topology, stencils, begin, std::min(begin + kPiece, static_cast<std::size_t>(n)),
                        begin);
    });
  }

  bool beginStencils(const dem::ParticleSet& particles, const GridTopology& topology,
                     ParticleStencils& stencils) const override {
    const CartesianGrid& g = topology.grid;
    // Fast path when the points of every particle span less than one cell per axis: each point
    // then lies in one of two cells per axis, i.e. one of the 8 cells of a 2 x 2 x 2 block, and
    // the stencil is 8 point counts (no search). Cells are found exactly as by cellOf(x + r u).
    const double span = 2.0 * unit.reach * maxRadius(particles);
    const bool block = span < 0.999 * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    stencils.resize(particles.size(), block ? kBlockCapacity : kPoints);
    if (block) {
      if (!tables_ || !tables_->fits(topology)) tables_ = std::make_unique<BlockTables>(topology);
      return true;
    }
    forEachIndex(static_cast<std::int64_t>(particles.size()), 29, [&](std::int64_t p) {
      StencilWriter w(stencils, static_cast<std::size_t>(p));
      const Vec3 x = particles.position[p];
      const double r = particles.radius[p];
      for (int m = 0; m < kPoints; ++m) {
        const auto c = topology.cellOf(x + r * Vec3{unit.c[0][m], unit.c[1][m], unit.c[2][m]});
        w.add(topology.flat(c[0], c[1], c[2]), 1.0 / kPoints);
      }
      w.normalise();  // sum of 29 x (1/29) is 1 up to round-off; make it 1 to the last bit we can
    });
    return false;
  }

  void buildStencilRange(const dem::ParticleSet& particles, const GridTopology& topology, ParticleStencils& out,
                         std::size_t begin, std::size_t end, std::size_t first) const override {
    if (out.capacity != kBlockCapacity) return;  // general path: built by beginStencils
    const BlockTables& tables = *tables_;
    const std::size_t entryShift = first - begin;  // particle p at entry p + entryShift (modulo 2^64)
#if defined(GF_X86_SIMD)
    if (blockPathAvx512.enabled()) {
      addBlocksAvx512(particles, topology, tables, out, begin, end, entryShift);
      return;
    }
#endif
    ScaledPoints points;
    for (std::size_t p = begin; p < end; ++p) {
      if (!points.scaledFor(particles.radius[p])) points.scale(particles.radius[p]);
      const std::size_t entry = p + entryShift;
      addBlock(topology, tables, points, particles.position[p], out.cell.data() + entry * kBlockCapacity,
               out.weight.data() + entry * kBlockCapacity, out.count[entry]);
    }
  }

 private:
  // the block path's stencil capacity; the general path's is kPoints = 29, so the capacity tells
  // buildStencilRange which path beginStencils took
  static constexpr int kBlockCapacity = 8;

  /// What the block path needs of the grid, built once per grid.
  struct BlockTables {
    std::array<int, 3> cells;
    int ghosts;
    std::array<bool, 3> periodic;
    AxisOffsets axis[3];
    std::size_t shift;             // flat(0, 0, 0)
    double weightOf[kPoints + 1];  // weight of a cell holding c points
    /// Per axis and lower cell lo (kFirst .. cells + 1): the axis's offsets of the 8 block cells
    /// (lane b: lo or lo + 1 by bit a of b) and whether both cells map to one (fold mask, ~0)
    struct alignas(64) BlockLanes {
      std::int64_t lane[8];
    };
    std::vector<BlockLanes> lanes[3];
    std::vector<std::uint64_t> fold[3];
    explicit BlockTables(const GridTopology& t)
        : cells(t.grid.cells),
          ghosts(t.grid.ghosts),
          periodic(t.periodic),
          axis{{t, 0, 1}, {t, 1, extent(t, 0)}, {t, 2, extent(t, 0) * extent(t, 1)}},
          shift(static_cast<std::size_t>(t.grid.ghosts) * (extent(t, 0) * extent(t, 1) + extent(t, 0) + 1)) {
      for (int c = 0; c <= kPoints; ++c) weightOf[c] = c * (1.0 / kPoints);
      for (int a = 0; a < 3; ++a)
        for (int lo = AxisOffsets::kFirst; lo <= cells[a] + 1; ++lo) {
          std::size_t offset[2];
          axis[a].pair(t, lo, offset[0], offset[1]);
          BlockLanes l;
          for (int b = 0; b < 8; ++b) l.lane[b] = static_cast<std::int64_t>(offset[(b >> a) & 1]);
          lanes[a].push_back(l);
          fold[a].push_back(offset[0] == offset[1] ? ~0ull : 0ull);
        }
    }
    bool fits(const GridTopology& t) const {
      return cells == t.grid.cells && ghosts == t.grid.ghosts && periodic == t.periodic;
    }
    static std::size_t extent(const GridTopology& t, int a) {
      return static_cast<std::size_t>(t.grid.cells[a]) + 2 * static_cast<std::size_t>(t.grid.ghosts);
    }
  };
  // built by beginStencils (one thread), only read by buildStencilRange (any thread)
  mutable std::unique_ptr<BlockTables> tables_;

  /// The block stencil of the particle at x into cell[0..8), weight[0..8), count.
  static void addBlock(const GridTopology& t, const BlockTables& tables, const ScaledPoints& points, const Vec3& x,
                       std::size_t* cell, double* weight, int& count) {
    const AxisOffsets (&axisOffsets)[3] = tables.axis;
    std::size_t offset[3][2];  // flat(i, j, k) = offset[0][.] + offset[1][.] + offset[2][.] + shift
    const AxisSplit sx = splitAxis(x.x, points.value[0], t.grid.origin.x, t.inverseSpacing.x);
    const AxisSplit sy = splitAxis(x.y, points.value[1], t.grid.origin.y, t.inverseSpacing.y);
    const AxisSplit sz = splitAxis(x.z, points.value[2], t.grid.origin.z, t.inverseSpacing.z);
    axisOffsets[0].pair(t, sx.lo, offset[0][0], offset[0][1]);
    axisOffsets[1].pair(t, sy.lo, offset[1][0], offset[1][1]);
    axisOffsets[2].pair(t, sz.lo, offset[2][0], offset[2][1]);
    // the 8 cell counts of the table, one byte each (byte b: cell bit0 x + bit1 y + bit2 z)
    // axes whose two cells map to the same cell (wall fold, one-cell periodic axis): add the upper
    // bytes onto the lower ones (branch-free, in registers: which axes fold is hard to predict)
    const std::uint64_t counts = foldCounts(unit.packedCount[sx.split][sy.split][sz.split], offset);
    // the non-empty cells in block order, branch-free (which cells are empty is hard to predict):
    // entry b goes to slot = number of non-empty cells before it (byte-wise prefix sums of the
    // non-empty flags by one multiplication); an empty cell's entry is overwritten by the next
    // non-empty one or lies beyond the count (capacity 8)
    constexpr std::uint64_t ones = 0x0101010101010101ull;
    const std::uint64_t nonEmpty = (counts | counts >> 1 | counts >> 2 | counts >> 3 | counts >> 4) & ones;
    const std::uint64_t inclusive = nonEmpty * ones;  // byte b: non-empty cells 0..b (<= 8, no carry)
    const std::uint64_t slots = inclusive - nonEmpty;  // byte b: non-empty cells before b
    for (int b = 0; b < 8; ++b) {
      const auto c = static_cast<int>((counts >> (8 * b)) & 0xFF);
      const auto slot = static_cast<int>((slots >> (8 * b)) & 0xFF);
      cell[slot] = offset[0][b & 1] + offset[1][(b >> 1) & 1] + offset[2][(b >> 2) & 1] + tables.shift;
      weight[slot] = tables.weightOf[c];
    }
    count = static_cast<int>(inclusive >> 56);
  }

  /// Folds the upper bytes of the axes whose two cells map to one cell onto the lower ones (as addBlock).
  static std::uint64_t foldCounts(std::uint64_t counts, const std::size_t (&offset)[3][2]) {
    return foldCountsWith(counts, {offset[0][0] == offset[0][1] ? ~0ull : 0ull,
                                   offset[1][0] == offset[1][1] ? ~0ull : 0ull,
                                   offset[2][0] == offset[2][1] ? ~0ull : 0ull});
  }
  /// foldCounts with the fold masks per axis given (~0: the axis folds).
  static std::uint64_t foldCountsWith(std::uint64_t counts, const std::array<std::uint64_t, 3>& fold) {
    constexpr std::uint64_t lowerHalf[3] = {0x00FF00FF00FF00FFull, 0x0000FFFF0000FFFFull, 0x00000000FFFFFFFFull};
    for (int a = 0; a < 3; ++a) {
      const std::uint64_t keep = lowerHalf[a] | ~fold[a];
      counts = (counts & keep) + ((counts >> (8 << a)) & lowerHalf[a] & fold[a]);
    }
    return counts;
  }

#if defined(GF_X86_SIMD)
// GCC 12's _mm512_undefined_* (avx512fintrin.h: `__m512d __Y = __Y;`) is reported as "may be used
// uninitialized" where it is inlined into a masked intrinsic (GCC bug 105593, fixed in GCC 13); the
// two AVX-512 functions below pass it only as the don't-care source of an all-ones mask.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
  /// The lower cells and splits (as splitAxis) of the 8 particles from `first` into lane q0..q0+7
  /// of lower/split, one particle per vector lane: per axis and unit coordinate v the same
  /// operations (x + r u_v - origin) * inv as the per-particle form, the floor by rounding down
  /// (floorToInt of a value in int range), the split as 1 + the number of upper coordinates below
  /// lo + 1. Returns false (nothing written) where the radii differ or a lower cell lies outside
  /// the offset tables (the caller takes the per-particle form from there).
  __attribute__((target("avx512f,avx512vl,avx2,popcnt"))) static bool splitGroupOf8(
      const Vec3* position, const double* radius, std::size_t first, const GridTopology& t, const BlockTables& tables,
      ScaledPoints& points, int (&lower)[3][16], int (&split)[3][16], int q0) {
    const __m512d r = _mm512_loadu_pd(radius + first);
    if (_mm512_cmp_pd_mask(r, _mm512_set1_pd(radius[first]), _CMP_EQ_OQ) != 0xFF) return false;
    if (!points.scaledFor(radius[first])) points.scale(radius[first]);
    const double origin[3] = {t.grid.origin.x, t.grid.origin.y, t.grid.origin.z};
    const double inv[3] = {t.inverseSpacing.x, t.inverseSpacing.y, t.inverseSpacing.z};
    // the 8 positions as 24 doubles in three vectors, coordinate a of lane l at 3 l + a (from the
    // first two vectors below 16, else from the third)
    const double* base = &position[first].x;
    const __m512d first16[2] = {_mm512_loadu_pd(base), _mm512_loadu_pd(base + 8)};
    const __m512d last8 = _mm512_loadu_pd(base + 16);
    __m256i lo[3], count[3];
    for (int a = 0; a < 3; ++a) {
      const __m512i element = _mm512_add_epi64(_mm512_set_epi64(21, 18, 15, 12, 9, 6, 3, 0), _mm512_set1_epi64(a));
      const __mmask8 fromLast = _mm512_cmpge_epi64_mask(element, _mm512_set1_epi64(16));
      const __m512d x = _mm512_mask_permutexvar_pd(_mm512_permutex2var_pd(first16[0], element, first16[1]), fromLast,
                                                   element, last8);
      const __m512d o = _mm512_set1_pd(origin[a]), h = _mm512_set1_pd(inv[a]);
      const __m512d lowest = _mm512_mul_pd(_mm512_sub_pd(_mm512_add_pd(x, _mm512_set1_pd(points.value[a][0])), o), h);
      const __m512d floorOf = _mm512_roundscale_pd(lowest, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
      lo[a] = _mm512_cvtpd_epi32(floorOf);  // exact (an integer; NaN or out of range: INT_MIN)
      // inside the offset tables (kFirst .. cells + 1 for the pair), else the per-particle form
      const __m256i first = _mm256_set1_epi32(AxisOffsets::kFirst), last = _mm256_set1_epi32(tables.cells[a] + 1);
      if (_mm256_cmplt_epi32_mask(lo[a], first) || _mm256_cmpgt_epi32_mask(lo[a], last)) return false;
      const __m512d upper = _mm512_add_pd(floorOf, _mm512_set1_pd(1.0));  // lo + 1.0 exactly
      __m256i s = _mm256_set1_epi32(1);  // the lowest coordinate lies below lo + 1
      if (origin[a] == 0.0 && !std::signbit(origin[a])) {
        // y - (+0) is y for every y: the subtraction left out (the same bits)
        for (int v = 1; v < kValues; ++v) {
          const __m512d scaled = _mm512_mul_pd(_mm512_add_pd(x, _mm512_set1_pd(points.value[a][v])), h);
          s = _mm256_mask_add_epi32(s, _mm512_cmp_pd_mask(scaled, upper, _CMP_LT_OQ), s, _mm256_set1_epi32(1));
        }
      } else {
        for (int v = 1; v < kValues; ++v) {
          const __m512d scaled =
              _mm512_mul_pd(_mm512_sub_pd(_mm512_add_pd(x, _mm512_set1_pd(points.value[a][v])), o), h);
          s = _mm256_mask_add_epi32(s, _mm512_cmp_pd_mask(scaled, upper, _CMP_LT_OQ), s, _mm256_set1_epi32(1));
        }
      }
      count[a] = s;
    }
    for (int a = 0; a < 3; ++a) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(lower[a] + q0), lo[a]);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(split[a] + q0), count[a]);
    }
    return true;
  }

  /// addBlock for particles [begin, end) with AVX-512: per axis the 8 upper coordinates compared
  /// with the cell face in one instruction (the same operations per coordinate as splitAxis), the
  /// 8 cells and weights (count x (1/29), the values of weightOf) built in one register each and
  /// the non-empty ones compressed to the front. The same stencil entries as addBlock (entries
  /// beyond the count are zero instead of leftovers; nothing reads them), particle p's at entry
  /// p + entryShift of `stencils`.
  __attribute__((target("avx512f,avx2,popcnt"))) static void addBlocksAvx512(
      const dem::ParticleSet& particles, const GridTopology& t, const BlockTables& tables, ParticleStencils& stencils,
      std::size_t begin, std::size_t end, std::size_t entryShift) {
    const AxisOffsets (&axisOffsets)[3] = tables.axis;
    ScaledPoints points;
    __m512d upperPoints[3];  // r u_v of the 8 upper coordinates (v = 1..8) per axis
    const double origin[3] = {t.grid.origin.x, t.grid.origin.y, t.grid.origin.z};
    const double inv[3] = {t.inverseSpacing.x, t.inverseSpacing.y, t.inverseSpacing.z};
    const __m512i lane = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
    __mmask8 upperLanes[3];  // lanes b with bit a set take the upper cell of axis a
    for (int a = 0; a < 3; ++a) upperLanes[a] = _mm512_test_epi64_mask(lane, _mm512_set1_epi64(1ll << a));
    const __m512d weightPerPoint = _mm512_set1_pd(1.0 / kPoints);
    const __m512i shift = _mm512_set1_epi64(static_cast<long long>(tables.shift));
    const Vec3* position = particles.position.data();
    const double* radius = particles.radius.data();
    std::size_t* cellOut = stencils.cell.data();
    double* weightOut = stencils.weight.data();
    int* countOut = stencils.count.data();
    // batches in two passes (lower cells and splits; then offsets, counts and entries): the long
    // dependency chain of one particle overlaps with those of the next ones
    constexpr int kBatch = 16;
    for (std::size_t b0 = begin; b0 < end; b0 += kBatch) {
      const int size = static_cast<int>(std::min<std::size_t>(kBatch, end - b0));
      int lower[3][kBatch], split[3][kBatch];
      int q0 = 0;
      // groups of 8 particles of one radius side by side (one lane each): the same operations
      // per coordinate as the per-particle form below
      for (; q0 + 8 <= size; q0 += 8)
        if (!splitGroupOf8(position, radius, b0 + q0, t, tables, points, lower, split, q0)) break;
      for (int q = q0; q < size; ++q) {
        const std::size_t p = b0 + q;
        if (!points.scaledFor(radius[p])) points.scale(radius[p]);
        for (int a = 0; a < 3; ++a) upperPoints[a] = _mm512_loadu_pd(points.value[a] + 1);
        for (int a = 0; a < 3; ++a) {
          const double xa = position[p][a];
          const int lo = floorToInt((xa + points.value[a][0] - origin[a]) * inv[a]);
          const __m512d scaled = _mm512_mul_pd(
              _mm512_sub_pd(_mm512_add_pd(_mm512_set1_pd(xa), upperPoints[a]), _mm512_set1_pd(origin[a])),
              _mm512_set1_pd(inv[a]));
          const __mmask8 below = _mm512_cmp_pd_mask(scaled, _mm512_set1_pd(lo + 1.0), _CMP_LT_OQ);
          lower[a][q] = lo;
          split[a][q] = 1 + _mm_popcnt_u32(static_cast<unsigned>(below));
        }
      }
      for (int q = 0; q < size; ++q) {
        const std::size_t p = b0 + q;
        // the block's cells and fold masks from the per-axis tables (lower cells inside them; the
        // same integers as pair() and foldCounts), else as addBlock
        const auto kx = static_cast<std::size_t>(lower[0][q] - AxisOffsets::kFirst);
        const auto ky = static_cast<std::size_t>(lower[1][q] - AxisOffsets::kFirst);
        const auto kz = static_cast<std::size_t>(lower[2][q] - AxisOffsets::kFirst);
        __m512i cells;
        std::uint64_t counts = unit.packedCount[split[0][q]][split[1][q]][split[2][q]];
        if (kx < tables.fold[0].size() && ky < tables.fold[1].size() && kz < tables.fold[2].size()) {
          cells = _mm512_add_epi64(
              _mm512_add_epi64(shift, _mm512_load_si512(tables.lanes[0][kx].lane)),
              _mm512_add_epi64(_mm512_load_si512(tables.lanes[1][ky].lane), _mm512_load_si512(tables.lanes[2][kz].lane)));
          counts = foldCountsWith(counts, {tables.fold[0][kx], tables.fold[1][ky], tables.fold[2][kz]});
        } else {
          std::size_t offset[3][2];
          cells = shift;
          for (int a = 0; a < 3; ++a) {
            axisOffsets[a].pair(t, lower[a][q], offset[a][0], offset[a][1]);
            cells = _mm512_add_epi64(cells, _mm512_mask_blend_epi64(upperLanes[a],
                                                                    _mm512_set1_epi64(static_cast<long long>(offset[a][0])),
                                                                    _mm512_set1_epi64(static_cast<long long>(offset[a][1]))));
          }
          counts = foldCounts(counts, offset);
        }
        const __m128i bytes = _mm_cvtsi64_si128(static_cast<long long>(counts));
        const __m512i count64 = _mm512_cvtepu8_epi64(bytes);
        const __mmask8 nonEmpty = _mm512_test_epi64_mask(count64, count64);
        const __m512d weights = _mm512_mul_pd(_mm512_cvtepi32_pd(_mm256_cvtepu8_epi32(bytes)), weightPerPoint);
        const std::size_t entry = p + entryShift;  // (stencils at entry p + entryShift)
        _mm512_storeu_si512(cellOut + entry * kBlockCapacity, _mm512_maskz_compress_epi64(nonEmpty, cells));
        _mm512_storeu_pd(weightOut + entry * kBlockCapacity, _mm512_maskz_compress_pd(nonEmpty, weights));
        countOut[entry] = _mm_popcnt_u32(static_cast<unsigned>(nonEmpty));
      }
    }
  }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif
};

}  // namespace

void allowDividedAvx512(bool allowed) { blockPathAvx512.allow(allowed); }

GF_REGISTER_MODEL(VoidFractionScheme, DividedVoidFraction, "divided",
                  "satellite points: volume split into 29 equal parts at the centre and 28 points inside the sphere (CFDEM 'divided')")
}  // namespace gf::coupling
