#include "dem/neighbour_list.hpp"

#include <algorithm>
#include <cmath>

#include "core/cpu_features.hpp"
#include "core/parallel.hpp"

#if defined(GF_X86_SIMD)
#include <immintrin.h>
#endif

namespace gf::dem {

namespace {
VectorForm candidateTestAvx512(InstructionSet::Avx512fVl);  // keepRowAvx512
}  // namespace

void allowNeighbourAvx512(bool allowed) { candidateTestAvx512.allow(allowed); }

int CellGrid::cellIndex(const Vec3& x, int c[3]) const {
  for (int a = 0; a < 3; ++a) {
    const int k = static_cast<int>(std::floor((x[a] - origin[a]) / width[a]));
    c[a] = std::clamp(k, 0, dims[a] - 1);  // particles slightly outside go to the boundary cells
  }
  return (c[2] * dims[1] + c[1]) * dims[0] + c[0];
}

void CellGrid::build(const std::vector<Vec3>& x, const Vec3& boxMin, const Vec3& boxMax, double minCellSize) {
  const std::size_t n = x.size();
  const Vec3 size = boxMax - boxMin;
  // Cells at least the interaction range wide; coarser if the box would need far more cells
  // than particles (sparse systems).
  double h = minCellSize > 0.0 ? minCellSize : std::max({size.x, size.y, size.z});
  const double maxCells = 8.0 * static_cast<double>(n) + 4096.0;
  while (std::max(1.0, std::floor(size.x / h)) * std::max(1.0, std::floor(size.y / h)) *
             std::max(1.0, std::floor(size.z / h)) > maxCells)
    h *= 1.26;
  origin = boxMin;
  for (int a = 0; a < 3; ++a) {
    dims[a] = std::max(1, static_cast<int>(std::floor(size[a] / h)));
    width[a] = size[a] / dims[a];  // >= h; the cells tile the box exactly (periodic wrap)
  }
  // Finer cells along x where the cell count stays moderate (4 bytes per cell, temporary).
  xSplit = 1;
  for (int split = 3; split > 1 && xSplit == 1; --split) {
    const int splitDims = std::max(1, static_cast<int>(std::floor(size.x * split / h)));
    if (static_cast<double>(splitDims) * dims[1] * dims[2] <= 3.0 * maxCells && splitDims >= dims[0] * split) {
      xSplit = split;
      dims[0] = splitDims;
      width[0] = size.x / dims[0];  // >= h / split
    }
  }
  const std::size_t cells = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  cellStart.assign(cells + 1, 0);
  cellOf.resize(n);
  coordOf.resize(n);
  parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t i) {
    int c[3];
    cellOf[i] = static_cast<std::uint32_t>(cellIndex(x[i], c));
    coordOf[i] = {c[0], c[1], c[2]};
  });
  // Counting sort in place (no copy of the cell starts as fill cursors): count into cell c's own
  // slot, inclusive prefix sum (slot c: end of cell c), then place the particles backwards with
  // --slot, which leaves slot c at the start of cell c and each cell ascending.
  for (std::size_t i = 0; i < n; ++i) ++cellStart[cellOf[i]];
  for (std::size_t c = 1; c < cells; ++c) cellStart[c] += cellStart[c - 1];
  cellStart[cells] = static_cast<std::uint32_t>(n);
  sorted.resize(n);
  for (std::size_t i = n; i-- > 0;) sorted[--cellStart[cellOf[i]]] = static_cast<std::uint32_t>(i);
}

namespace {

std::uint64_t spreadBits(std::uint64_t v) {  // 21 bits -> every third bit
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// Runs of consecutive cells along x within `reach` cells of c (wrapped if periodic): [first,
/// last] pairs, at most 2 (a periodic wrap), each cell once.
int xCellRuns(int c, int dim, int reach, bool periodic, int (*runs)[2]) {
  if (2 * reach + 1 >= dim) {
    runs[0][0] = 0, runs[0][1] = dim - 1;
    return 1;
  }
  const int first = c - reach, last = c + reach;
  if (!periodic || (first >= 0 && last < dim)) {
    runs[0][0] = std::max(first, 0), runs[0][1] = std::min(last, dim - 1);
    return 1;
  }
  // wrapped: [0, last - dim] or [first + dim, dim - 1] beside the in-range part (no overlap: 2 reach + 1 < dim)
  if (first < 0) {
    runs[0][0] = 0, runs[0][1] = last;
    runs[1][0] = first + dim, runs[1][1] = dim - 1;
  } else {
    runs[0][0] = 0, runs[0][1] = last - dim;
    runs[1][0] = first, runs[1][1] = dim - 1;
  }
  return 2;
}

/// Neighbour cell offsets along one axis: -1, 0, +1, wrapped if periodic, without repeats.
int neighbourCells(int c, int dim, bool periodic, int out[3]) {
  int count = 0;
  for (int d = -1; d <= 1; ++d) {
    int k = c + d;
    if (periodic) k = (k + dim) % dim;
    else if (k < 0 || k >= dim) continue;
    bool seen = false;
    for (int q = 0; q < count; ++q) seen |= out[q] == k;
    if (!seen) out[count++] = k;
  }
  return count;
}

}  // namespace

std::uint64_t mortonCode(const Vec3& x, const Vec3& boxMin, double cellSize) {
  std::uint64_t k = 0;
  for (int a = 0; a < 3; ++a) {
    const double q = std::floor((x[a] - boxMin[a]) / cellSize);
    const std::uint64_t c = static_cast<std::uint64_t>(std::clamp(q, 0.0, 2097151.0));
    k |= spreadBits(c) << a;
  }
  return k;
}

std::vector<std::uint32_t> orderByKey(const std::vector<std::uint64_t>& key) {
  const std::size_t n = key.size();
  // Stable LSD radix sort of the indices by key, 8 bits a pass over the bits any key uses (3 x 8
  // bits for up to 256 cells per axis): ties stay in index order, the order a comparison sort by
  // (key, index) gives, in O(n) per pass instead of O(n log n) comparisons.
  std::uint64_t used = 0;
  for (std::size_t i = 0; i < n; ++i) used |= key[i];
  std::vector<std::uint32_t> order(n), next(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  for (int shift = 0; shift < 64 && (used >> shift) != 0; shift += 8) {
    std::uint32_t start[257] = {};
    for (std::size_t i = 0; i < n; ++i) ++start[((key[i] >> shift) & 0xff) + 1];
    for (int b = 0; b < 256; ++b) start[b + 1] += start[b];
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t i = order[k];
      next[start[(key[i] >> shift) & 0xff]++] = i;
    }
    order.swap(next);
  }
  return order;
}

/// Order of `subset` (indices into the arrays) by (orderKey, id).
void sortByKeyThenId(std::vector<std::uint32_t>& subset, const ParticleSet& p) {
  auto before = [&](std::uint32_t a, std::uint32_t b) {
    return p.orderKey[a] != p.orderKey[b] ? p.orderKey[a] < p.orderKey[b] : p.id[a] < p.id[b];
  };
  if (std::is_sorted(subset.begin(), subset.end(), before)) return;
  // Radix sort by key (stable), then each run of equal keys by id.
  std::vector<std::uint64_t> keys(subset.size());
  for (std::size_t k = 0; k < subset.size(); ++k) keys[k] = p.orderKey[subset[k]];
  const std::vector<std::uint32_t> byKey = orderByKey(keys);
  std::vector<std::uint32_t> sorted(subset.size());
  for (std::size_t k = 0; k < subset.size(); ++k) sorted[k] = subset[byKey[k]];
  for (std::size_t a = 0; a < sorted.size();) {
    std::size_t b = a + 1;
    while (b < sorted.size() && p.orderKey[sorted[b]] == p.orderKey[sorted[a]]) ++b;
    if (b - a > 1)
      std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(a), sorted.begin() + static_cast<std::ptrdiff_t>(b),
                [&](std::uint32_t x, std::uint32_t y) { return p.id[x] < p.id[y]; });
    a = b;
  }
  subset.swap(sorted);
}

std::vector<std::uint32_t> mortonOrder(const std::vector<Vec3>& x, const Vec3& boxMin, const Vec3& /*boxMax*/,
                                       double cellSize) {
  std::vector<std::uint64_t> key(x.size());
  parallelFor(static_cast<std::int64_t>(x.size()),
              [&](std::int64_t i) { key[i] = mortonCode(x[i], boxMin, cellSize); });
  return orderByKey(key);
}

namespace {

/// Candidates tested per range with a fixed trip count (keepCandidates).
constexpr std::uint32_t kFixedCandidates = 5;

/// Position and radius side by side in cell order: the candidates of a row of cells are one
/// contiguous range.
struct CellSortedSphere {
  Vec3 x;
  double r;
};

/// The candidate spheres in cell order as one array per coordinate (the AVX-512 test loads eight
/// of each at once).
struct CellSortedSpheres {
  std::vector<double> x, y, z, r;
};

#if defined(GF_X86_SIMD)
/// keepCandidates for all `ranges` candidate ranges of a row ([first, last) pairs in the cell
/// order), eight candidates at a time: lane by lane the same differences, minimum images, squared
/// distances ((dx dx + dy dy) + dz dz, every product and sum rounded as in the scalar form: no FMA),
/// cut-offs and comparisons, so the same partners are kept, in candidate order (compressed in a
/// register: the compressing store is slow on some CPUs). Masked loads read nothing past a range;
/// `out` needs 8 writable slots past the kept ones. One iteration covers a range of up to 8
/// candidates (3-4 on average in a dense bed), where the scalar form tests 5 slots one by one.
/// Returns how many were kept; with Count, adds the touching ones to `touching`.
template <bool Periodic, bool Count>
__attribute__((target("avx512f,avx512vl"))) std::uint32_t keepRowAvx512(
    const CellSortedSpheres& spheres, const std::uint32_t (*range)[2], int ranges, const std::uint32_t* sorted,
    const Vec3& xi, double reach, double radius, std::uint32_t self, const PeriodicBox& box, std::uint32_t* out,
    std::uint32_t& touching) {
  const double* const X = spheres.x.data();
  const double* const Y = spheres.y.data();
  const double* const Z = spheres.z.data();
  const double* const R = spheres.r.data();
  const __m512d centre[3] = {_mm512_set1_pd(xi.x), _mm512_set1_pd(xi.y), _mm512_set1_pd(xi.z)};
  const __m512d vReach = _mm512_set1_pd(reach), vRadius = _mm512_set1_pd(radius);
  const __m256i vSelf = _mm256_set1_epi32(static_cast<int>(self));
  std::uint32_t kept = 0, touches = 0;
  for (int q = 0; q < ranges; ++q) {
    const std::uint32_t last = range[q][1];
    for (std::uint32_t s = range[q][0]; s < last; s += 8) {
      const std::uint32_t left = last - s;
      const __mmask8 lanes = left >= 8 ? __mmask8(0xff) : static_cast<__mmask8>((1u << left) - 1u);
      __m512d d[3] = {_mm512_sub_pd(centre[0], _mm512_maskz_loadu_pd(lanes, X + s)),
                      _mm512_sub_pd(centre[1], _mm512_maskz_loadu_pd(lanes, Y + s)),
                      _mm512_sub_pd(centre[2], _mm512_maskz_loadu_pd(lanes, Z + s))};
      if constexpr (Periodic) {
        // PeriodicBox::minimumImage: d - L where d > L/2, else d + L where d < -L/2
        for (int a = 0; a < 3; ++a)
          if (box.periodic[a]) {
            const __m512d half = _mm512_set1_pd(box.half[a]), length = _mm512_set1_pd(box.length[a]);
            const __mmask8 high = _mm512_cmp_pd_mask(d[a], half, _CMP_GT_OQ);
            const __mmask8 low = _mm512_cmp_pd_mask(d[a], _mm512_sub_pd(_mm512_setzero_pd(), half), _CMP_LT_OQ);
            d[a] = _mm512_mask_sub_pd(d[a], high, d[a], length);
            d[a] = _mm512_mask_add_pd(d[a], low, d[a], length);
          }
      }
      const __m512d distance2 = _mm512_add_pd(
          _mm512_add_pd(_mm512_mul_pd(d[0], d[0]), _mm512_mul_pd(d[1], d[1])), _mm512_mul_pd(d[2], d[2]));
      const __m512d r = _mm512_maskz_loadu_pd(lanes, R + s);
      const __m512d cut = _mm512_add_pd(vReach, r);
      const __m256i j = _mm256_maskz_loadu_epi32(lanes, sorted + s);
      const __mmask8 above = _mm256_mask_cmpgt_epu32_mask(lanes, j, vSelf);
      const __mmask8 keep = _mm512_mask_cmp_pd_mask(above, distance2, _mm512_mul_pd(cut, cut), _CMP_LT_OQ);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + kept), _mm256_maskz_compress_epi32(keep, j));
      kept += static_cast<std::uint32_t>(__builtin_popcount(keep));
      if constexpr (Count) {
        const __m512d rsum = _mm512_add_pd(vRadius, r);
        touches += static_cast<std::uint32_t>(
            __builtin_popcount(_mm512_mask_cmp_pd_mask(above, distance2, _mm512_mul_pd(rsum, rsum), _CMP_LT_OQ)));
      }
    }
  }
  touching += touches;
  return kept;
}
#endif

/// Appends to `out` the candidates s in [0, count) of one contiguous range that are partners of
/// row `self`: j = sorted[s] > self and |xi - x_s| < reach + r_s (minimum image if Periodic).
/// Returns how many; with Count, adds to `touching` how many of them touch (|xi - x_s| < radius +
/// r_s, the distances NeighbourList::countTouching computes).
template <bool Periodic, bool Count>
[[gnu::always_inline]] inline std::uint32_t keepCandidates(const CellSortedSphere* spheres, const std::uint32_t* sorted,
                                                           std::uint32_t count, const Vec3& xi, double reach,
                                                           double radius, std::uint32_t self, const PeriodicBox& box,
                                                           std::uint32_t* out, std::uint32_t& touching) {
  std::uint32_t kept = 0;
  // Branch-free (half the candidates have j <= self, at random: a branch on it mispredicts).
  // The first kFixedCandidates slots are tested whatever the range's count, the slots past it
  // masked off (the arrays are padded): a loop of the range's own length (3 candidates on average
  // in a dense bed) mispredicts its exit on nearly every range, which cost more than testing the
  // empty slots (BM_DemNeighbourBuild -13 % with 5 slots; 3, 4 and 6 did less). The rare longer ranges finish in a second loop.
  for (std::uint32_t s = 0; s < kFixedCandidates; ++s) {
    const std::uint32_t j = sorted[s];
    const Vec3 dx = Periodic ? box.minimumImage(xi - spheres[s].x) : xi - spheres[s].x;
    const double cut = reach + spheres[s].r;
    const double distance2 = normSquared(dx);
    const bool inRange = s < count;
    out[kept] = j;
    kept += inRange & (j > self) & (distance2 < cut * cut) ? 1u : 0u;
    if constexpr (Count) {
      const double rsum = radius + spheres[s].r;
      touching += inRange & (j > self) & (distance2 < rsum * rsum) ? 1u : 0u;
    }
  }
  for (std::uint32_t s = kFixedCandidates; s < count; ++s) {
    const std::uint32_t j = sorted[s];
    const Vec3 dx = Periodic ? box.minimumImage(xi - spheres[s].x) : xi - spheres[s].x;
    const double cut = reach + spheres[s].r;
    const double distance2 = normSquared(dx);
    out[kept] = j;
    kept += (j > self) & (distance2 < cut * cut) ? 1u : 0u;
    if constexpr (Count) {
      const double rsum = radius + spheres[s].r;
      touching += (j > self) & (distance2 < rsum * rsum) ? 1u : 0u;
    }
  }
  return kept;
}

}  // namespace

void NeighbourList::build(const ParticleSet& p, const PeriodicBox& box, const Vec3& boxMin, const Vec3& boxMax,
                          double skin, const std::vector<std::int64_t>& previousIndex, bool withRollingHistory) {
  ++version;
  const std::size_t n = p.size();
  double maxRadius = 0.0;
  for (double r : p.radius) maxRadius = std::max(maxRadius, r);
  CellGrid grid;
  grid.build(p.position, boxMin, boxMax, 2.0 * maxRadius + skin);
  // The spheres in cell order: one array per coordinate for the AVX-512 test (masked loads: no
  // padding), else side by side, padded like grid.sorted by kFixedCandidates (zeros) for
  // keepCandidates' fixed-length first loop.
  const bool simd = candidateTestAvx512.enabled();
  std::vector<CellSortedSphere> sphere;
  CellSortedSpheres soa;
  grid.sorted.resize(n + kFixedCandidates, 0);
  if (simd) {
    for (auto* v : {&soa.x, &soa.y, &soa.z, &soa.r}) v->resize(n);
    parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t s) {
      const std::uint32_t i = grid.sorted[s];
      const Vec3 x = p.position[i];
      soa.x[s] = x.x, soa.y[s] = x.y, soa.z[s] = x.z, soa.r[s] = p.radius[i];
    });
  } else {
    sphere.resize(n + kFixedCandidates);
    parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t s) {
      const std::uint32_t i = grid.sorted[s];
      sphere[s] = {p.position[i], p.radius[i]};
    });
  }

  // Appends the partners j > i within the cut-off, ascending (the force loop walks memory forwards
  // and knows the row's last partner). The cells along x of a (y, z) row of cells are consecutive
  // in the cell order: one range (two across a periodic wrap). The candidates are tested into a
  // per-thread scratch row through a raw pointer (no per-entry capacity check, no zero fill), the
  // few kept ones sorted there by insertion and appended.
  const CellSortedSphere* spheres = sphere.data();
  // Touching pairs per row for the force loop's split among threads (as countTouching, which a
  // restart calls, counts them: the same distances; only teams use them).
  const bool countingTouches = omp_get_max_threads() > 1;
  if (countingTouches) touchingStart.assign(n + 1, 0);
  else touchingStart.clear();
  const std::uint32_t* sorted = grid.sorted.data();
  const std::uint32_t* cellStart = grid.cellStart.data();
  auto appendPartners = [&]<bool Periodic, bool Simd>(std::size_t i, std::vector<std::uint32_t>& out) {
    const std::array<int, 3>& c = grid.coordOf[i];
    int ny[3], nz[3], runs[2][2];
    const int rx = xCellRuns(c[0], grid.dims[0], grid.xSplit, box.periodic[0], runs);
    const int cy = neighbourCells(c[1], grid.dims[1], box.periodic[1], ny);
    const int cz = neighbourCells(c[2], grid.dims[2], box.periodic[2], nz);
    std::uint32_t range[18][2];  // candidate ranges in the cell order
    int ranges = 0;
    std::uint32_t candidates = 0;
    for (int a = 0; a < cz; ++a)
      for (int b = 0; b < cy; ++b) {
        const int rowOfCells = (nz[a] * grid.dims[1] + ny[b]) * grid.dims[0];
        for (int d = 0; d < rx; ++d) {
          range[ranges][0] = cellStart[rowOfCells + runs[d][0]];
          range[ranges][1] = cellStart[rowOfCells + runs[d][1] + 1];
          candidates += range[ranges][1] - range[ranges][0];
          ++ranges;
        }
      }
    thread_local std::vector<std::uint32_t> scratchRow;
    // (+1: a masked slot's store; +8: the vector store of the AVX-512 test)
    if (scratchRow.size() < candidates + 8) scratchRow.resize(candidates + 8);
    std::uint32_t* const row = scratchRow.data();
    std::uint32_t kept = 0;
    const Vec3 xi = p.position[i];
    const double radius = p.radius[i], ri = radius + skin;
    const auto self = static_cast<std::uint32_t>(i);
    const PeriodicBox localBox = box;  // (the row stores cannot change it: no reloads)
    std::uint32_t touching = 0;
#if defined(GF_X86_SIMD)
    if constexpr (Simd) {
      kept = countingTouches ? keepRowAvx512<Periodic, true>(soa, range, ranges, sorted, xi, ri, radius, self, localBox,
                                                             row, touching)
                             : keepRowAvx512<Periodic, false>(soa, range, ranges, sorted, xi, ri, radius, self,
                                                              localBox, row, touching);
    }
#endif
    for (int q = 0; q < ranges && !Simd; ++q) {
      const std::uint32_t first = range[q][0], count = range[q][1] - first;
      kept += countingTouches ? keepCandidates<Periodic, true>(spheres + first, sorted + first, count, xi, ri, radius,
                                                               self, localBox, row + kept, touching)
                              : keepCandidates<Periodic, false>(spheres + first, sorted + first, count, xi, ri, radius,
                                                                self, localBox, row + kept, touching);
    }
    if (countingTouches) touchingStart[i + 1] = touching;
    constexpr std::uint32_t kRankSorted = 16;
    if (kept <= kRankSorted) {
      // Ascending by rank (the partners are distinct: each cell is in one range once): entry k goes
      // to the number of entries below it. Branch-free, unlike an insertion sort, whose branches
      // mispredict on the random order of the few entries.
      std::uint32_t ascending[kRankSorted];
      for (std::uint32_t k = 0; k < kept; ++k) {
        std::uint32_t rank = 0;
        for (std::uint32_t m = 0; m < kept; ++m) rank += row[m] < row[k] ? 1u : 0u;
        ascending[rank] = row[k];
      }
      out.insert(out.end(), ascending, ascending + kept);
      return;
    }
    for (std::uint32_t k = 1; k < kept; ++k) {  // insertion sort (long rows)
      const std::uint32_t value = row[k];
      std::uint32_t m = k;
      for (; m > 0 && row[m - 1] > value; --m) row[m] = row[m - 1];
      row[m] = value;
    }
    out.insert(out.end(), row, row + kept);
  };

  std::vector<std::uint32_t> oldStart = std::move(rowStart);
  std::vector<std::uint32_t> oldPartner = std::move(partner);
  std::vector<Vec3> oldTangential = std::move(tangentialHistory);
  std::vector<Vec3> oldRolling = std::move(rollingHistory);
  const bool carryRolling = withRollingHistory && oldRolling.size() == oldPartner.size();
  const std::int64_t oldRows = oldStart.empty() ? 0 : static_cast<std::int64_t>(oldStart.size()) - 1;

  // No particle moved in the arrays (the rebuilds between reorderings): every particle keeps its
  // index, old and new row i are both ascending, and one merge walk finds the persisting pairs.
  bool sameIndices = true;
  for (std::size_t k = 0; k < n && sameIndices; ++k)
    sameIndices = (k < previousIndex.size() ? previousIndex[k] : -1) ==
                  (static_cast<std::int64_t>(k) < oldRows ? static_cast<std::int64_t>(k) : -1);

  // Carries the history of the pairs of row i that were listed at the previous build.
  auto carryHistory = [&](std::size_t i) {
    const std::uint32_t first = rowStart[i], last = rowStart[i + 1];
    const std::int64_t oi = i < previousIndex.size() ? previousIndex[i] : -1;
    if (oi < 0 || oi >= oldRows) return;
    if (sameIndices) {
      std::uint32_t q = oldStart[i];
      const std::uint32_t qEnd = oldStart[i + 1];
      for (std::uint32_t k = first; k < last && q < qEnd; ++k) {
        const std::uint32_t j = partner[k];
        while (q < qEnd && oldPartner[q] < j) ++q;
        if (q < qEnd && oldPartner[q] == j) {  // (new particles j >= oldRows are in no old row)
          tangentialHistory[k] = oldTangential[q];
          if (carryRolling) rollingHistory[k] = oldRolling[q];
        }
      }
      return;
    }
    for (std::uint32_t k = first; k < last; ++k) {
      const std::uint32_t j = partner[k];
      const std::int64_t oj = j < previousIndex.size() ? previousIndex[j] : -1;
      if (oj < 0 || oj >= oldRows) continue;
      const std::int64_t owner = std::min(oi, oj), other = std::max(oi, oj);
      // old rows are ascending: stop at the first partner beyond `other`
      for (std::uint32_t q = oldStart[owner]; q < oldStart[owner + 1] && oldPartner[q] <= other; ++q)
        if (oldPartner[q] == static_cast<std::uint32_t>(other)) {
          const double sign = oi < oj ? 1.0 : -1.0;
          tangentialHistory[k] = sign * oldTangential[q];
          if (carryRolling) rollingHistory[k] = sign * oldRolling[q];
          break;
        }
    }
  };

  buildCompressedRows(
      n, scratch_, rowStart, partner,
      [&](std::size_t i, std::vector<std::uint32_t>& out) {
        if (simd) {
          if (box.anyPeriodic) appendPartners.template operator()<true, true>(i, out);
          else appendPartners.template operator()<false, true>(i, out);
        } else {
          if (box.anyPeriodic) appendPartners.template operator()<true, false>(i, out);
          else appendPartners.template operator()<false, false>(i, out);
        }
      },
      [&](std::size_t entries) {
        tangentialHistory.assign(entries, Vec3{});
        if (withRollingHistory) rollingHistory.assign(entries, Vec3{});
      },
      carryHistory,
      // a row's cost follows its candidates; the previous build's entries per row estimate them
      // (when the rows are the same particles)
      sameIndices && oldStart.size() == n + 1 ? oldStart.data() : nullptr);
  for (std::size_t i = 0; countingTouches && i < n; ++i) touchingStart[i + 1] += touchingStart[i];
}

void NeighbourList::countTouching(const std::vector<Vec3>& positionAtBuild, const std::vector<double>& radius,
                                  const PeriodicBox& box) {
  const std::size_t n = rows();
  // Only a split among threads uses the counts (one thread: none, and the force loop ignores an
  // empty touchingStart).
  if (omp_get_max_threads() <= 1 || positionAtBuild.size() != n || radius.size() != n) {
    touchingStart.clear();
    return;
  }
  touchingStart.assign(n + 1, 0);
  const Vec3* x = positionAtBuild.data();
  const double* r = radius.data();
  parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t i) {
    std::uint32_t touching = 0;
    for (std::uint32_t k = rowStart[i]; k < rowStart[i + 1]; ++k) {
      const std::uint32_t j = partner[k];
      const double reach = r[i] + r[j];
      touching += normSquared(box.minimumImage(x[i] - x[j])) < reach * reach ? 1u : 0u;
    }
    touchingStart[i + 1] = touching;
  });
  for (std::size_t i = 0; i < n; ++i) touchingStart[i + 1] += touchingStart[i];
}

std::size_t NeighbourList::memoryBytes() const {
  return (rowStart.capacity() + touchingStart.capacity()) * sizeof(std::uint32_t) +
         partner.capacity() * sizeof(std::uint32_t) +
         tangentialHistory.capacity() * sizeof(Vec3) + rollingHistory.capacity() * sizeof(Vec3);
}

void NeighbourList::save(BinaryWriter& out) const {
  out.putVector(rowStart);
  out.putVector(partner);
  out.putVector(tangentialHistory);
  out.putVector(rollingHistory);
}

void NeighbourList::load(BinaryReader& in) {
  ++version;
  rowStart = in.getVector<std::uint32_t>();
  partner = in.getVector<std::uint32_t>();
  tangentialHistory = in.getVector<Vec3>();
  rollingHistory = in.getVector<Vec3>();
  if (tangentialHistory.size() != partner.size() || (!rowStart.empty() && rowStart.back() != partner.size()))
    throw CheckpointError("checkpoint is corrupt: DEM neighbour list arrays do not match");
}

}  // namespace gf::dem
