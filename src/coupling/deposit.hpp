#pragma once
// Deposit of per-particle quantities onto cells with the particle stencils:
//   sum_c[ch] = sum_p w_pc value_p[ch]        (C channels at once)
// The result is channel-interleaved (sum[cell * C + ch], cell = Field::index of the grid), so one
// stencil entry touches one cache line. Deterministic for a given thread count: each thread
// accumulates its static block of particles into its own buffer; the buffers are then added in
// thread order per cell. The buffers live in DepositBuffers and are reused (no allocation per
// step once sized). Memory: threads x cells x C doubles (fine for the grids of unresolved
// CFD-DEM; a colouring scheme would avoid it).
//
// Each thread's buffer is all zero between deposits: a thread notes the range of cells its
// stencils touched, the merge reads a buffer only inside its range (a thread's particles, a
// contiguous block of a space-filling-curve order, cover a part of the grid), and each thread
// zeroes its own range afterwards. Outside its range a buffer holds +0.0, which adds nothing to a
// sum that starts at 0.0 (such a sum is never -0.0): the same bits as adding every buffer, without
// reading the other cores' zeros (a cache line moving between cores costs some hundred
// nanoseconds) and without a zero pass before the deposit.
#include <omp.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include "core/cpu_features.hpp"
#if defined(GF_X86_SIMD)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/parallel.hpp"
#include "coupling/stencil.hpp"

namespace gf::coupling {

inline constexpr std::int64_t kMinParallelDeposit = 4096;  // particles; below: one thread (no region)

struct DepositBuffers {
  std::vector<std::vector<double>> perThread;  // [thread][cell * C + ch], all zero between deposits
  std::vector<std::array<std::size_t, 2>> touched;  // [thread]: cells [first, end) of its last deposit
  std::vector<double> merged;                  // [cell * C + ch]
  /// The cells the stencils can reach as runs {first cell, cell count} (the interior rows of a
  /// grid with ghosts); only these are zeroed and summed, other entries of the result are
  /// undefined. Empty: all cells.
  std::vector<std::array<std::size_t, 2>> runs;
  /// Particles per thread (threadBlock: used when it is a split of this many particles for the
  /// team, else equal blocks). Not owned.
  const std::vector<std::size_t>* blocks = nullptr;
};

inline constexpr std::int64_t kDepositPiece = 256;  // particles per prepare call

/// The C values of one particle, held as channel pairs in SSE2 registers (built from the scalars,
/// not reloaded from memory: a 16-byte load of two 8-byte stores stalls store forwarding), so that
/// addTo adds w v to a cell's C sums two channels at a time: per lane the same multiplication and
/// addition as the scalar target[ch] += w * v[ch] (the same bits).
template <int C>
struct PackedValues {
#if defined(__SSE2__)
  __m128d pair[C / 2];
  double last = 0.0;  // channel C - 1 where C is odd
  explicit PackedValues(const double (&v)[C]) {
    for (int k = 0; k < C / 2; ++k) pair[k] = _mm_set_pd(v[2 * k + 1], v[2 * k]);
    if constexpr (C % 2 == 1) last = v[C - 1];
  }
  void addTo(double* target, double w) const {
    const __m128d w2 = _mm_set1_pd(w);
    for (int k = 0; k < C / 2; ++k)
      _mm_storeu_pd(target + 2 * k, _mm_add_pd(_mm_loadu_pd(target + 2 * k), _mm_mul_pd(w2, pair[k])));
    if constexpr (C % 2 == 1) target[C - 1] += w * last;
  }
#else
  double value[C];
  explicit PackedValues(const double (&v)[C]) {
    for (int ch = 0; ch < C; ++ch) value[ch] = v[ch];
  }
  void addTo(double* target, double w) const {
    for (int ch = 0; ch < C; ++ch) target[ch] += w * value[ch];
  }
#endif
};

/// Whether deposits of 4 or more channels may add four channels per operation (depositPieceWide):
/// the CPU has AVX2 and no test switched it off (allowWideDeposit).
inline VectorForm& wideDeposit() {
  static VectorForm form(InstructionSet::Avx2);
  return form;
}
inline void allowWideDeposit(bool allowed) { wideDeposit().allow(allowed); }
inline bool useWideDeposit() { return wideDeposit().enabled(); }

#if defined(GF_X86_SIMD)
/// The deposit of particles [begin, end) with four channels per 256-bit operation (then a pair,
/// then a single channel): per lane the same multiplication and addition as
/// target[ch] += w * v[ch] (no fused multiply-add: not enabled for this function), the same bits.
/// Widens [lowestCell, highestCell] to the cells written.
template <int C, class Values>
__attribute__((target("avx2"))) void depositPieceWide(const StencilPiece& piece, std::int64_t begin, std::int64_t end,
                                                      double* sum, Values& values, std::size_t& lowestCell,
                                                      std::size_t& highestCell) {
  // (the piece's arrays as plain pointers: the struct's would be reloaded after every store)
  const int* const countOf = piece.count;
  const std::size_t* const cellOf = piece.cell;
  const double* const weightOf = piece.weight;
  const std::size_t capacity = piece.capacity;
  std::size_t lowest = lowestCell, highest = highestCell;  // (locals: no store per entry)
  constexpr int kQuads = C / 4;
  constexpr int kPair = (C % 4) / 2;  // 0 or 1
  constexpr bool kLast = C % 2 == 1;
  for (std::int64_t p = begin; p < end; ++p) {
    double v[C];
    values(static_cast<std::size_t>(p), v);
    __m256d quad[kQuads];
    for (int k = 0; k < kQuads; ++k) quad[k] = _mm256_set_pd(v[4 * k + 3], v[4 * k + 2], v[4 * k + 1], v[4 * k]);
    __m128d pair = _mm_setzero_pd();
    if constexpr (kPair == 1) pair = _mm_set_pd(v[4 * kQuads + 1], v[4 * kQuads]);
    const double last = v[C - 1];
    const auto q = static_cast<std::size_t>(p - begin);  // (index in the piece)
    const std::size_t base = q * capacity;
    const int count = countOf[q];
    for (int e = 0; e < count; ++e) {
      const std::size_t cell = cellOf[base + e];
      lowest = std::min(lowest, cell);
      highest = std::max(highest, cell);
      double* target = sum + cell * C;
      const double w = weightOf[base + e];
      const __m256d w4 = _mm256_set1_pd(w);
      for (int k = 0; k < kQuads; ++k)
        _mm256_storeu_pd(target + 4 * k, _mm256_add_pd(_mm256_loadu_pd(target + 4 * k), _mm256_mul_pd(w4, quad[k])));
      if constexpr (kPair == 1)
        _mm_storeu_pd(target + 4 * kQuads,
                      _mm_add_pd(_mm_loadu_pd(target + 4 * kQuads), _mm_mul_pd(_mm_set1_pd(w), pair)));
      if constexpr (kLast) target[C - 1] += w * last;
    }
  }
  lowestCell = lowest;
  highestCell = highest;
}
#endif

/// values(p, double (&v)[C]) writes the C values of particle p. Returns the interleaved sums over
/// `cells` flat cells (over b.runs if set; valid until the next deposit with the same buffers).
/// prepare(thread, begin, end) runs on the depositing thread (0-based index in the team) just
/// before particles [begin, end) are deposited, pieces of kDepositPiece particles in particle
/// order per thread, and returns the StencilPiece of those particles: it may build their stencils
/// there (read back from cache), into `s` or into a buffer of its own for one piece (stencils
/// that nothing reads later then never go out to memory), and sum over them.
template <int C, class Values, class Prepare>
const std::vector<double>& depositChannels(const ParticleStencils& s, std::size_t cells, DepositBuffers& b,
                                           Values&& values, Prepare&& prepare) {
  const auto n = static_cast<std::int64_t>(s.size());
  const std::size_t size = cells * C;
  b.merged.resize(size);
  const int threads = n >= kMinParallelDeposit ? omp_get_max_threads() : 1;
  const std::array<std::size_t, 2> all{0, cells};
  const std::array<std::size_t, 2>* runs = b.runs.empty() ? &all : b.runs.data();
  const auto runCount = static_cast<std::int64_t>(b.runs.empty() ? 1 : b.runs.size());
  auto zero = [&](double* sum) {
    for (std::int64_t r = 0; r < runCount; ++r)
      std::fill(sum + runs[r][0] * C, sum + (runs[r][0] + runs[r][1]) * C, 0.0);
  };
  const bool wide = useWideDeposit();
  // returns the cells [first, end) the particles' stencils touched (first = end = 0: none)
  auto accumulate = [&](int thread, std::int64_t begin, std::int64_t end, double* sum) {
    std::size_t lowest = cells, highest = 0;
    for (std::int64_t piece = begin; piece < end; piece += kDepositPiece) {
      const std::int64_t pieceEnd = std::min(end, piece + kDepositPiece);
      const StencilPiece stencils =
          prepare(thread, static_cast<std::size_t>(piece), static_cast<std::size_t>(pieceEnd));
#if defined(GF_X86_SIMD)
      if constexpr (C >= 4) {
        if (wide) {
          depositPieceWide<C>(stencils, piece, pieceEnd, sum, values, lowest, highest);
          continue;
        }
      }
#endif
      // the stencil arrays as plain pointers (the struct's would be reloaded after every store)
      const int* const countOf = stencils.count;
      const std::size_t* const cellOf = stencils.cell;
      const double* const weightOf = stencils.weight;
      const std::size_t capacity = stencils.capacity;
      for (std::int64_t p = piece; p < pieceEnd; ++p) {
        double v[C];
        values(static_cast<std::size_t>(p), v);
        const PackedValues<C> packed(v);
        const auto q = static_cast<std::size_t>(p - piece);  // (index in the piece)
        const std::size_t base = q * capacity;
        const int count = countOf[q];
        for (int e = 0; e < count; ++e) {
          const std::size_t cell = cellOf[base + e];
          lowest = std::min(lowest, cell);
          highest = std::max(highest, cell);
          packed.addTo(sum + cell * C, weightOf[base + e]);
        }
      }
    }
    return lowest <= highest ? std::array<std::size_t, 2>{lowest, highest + 1} : std::array<std::size_t, 2>{0, 0};
  };
  if (threads == 1) {
    zero(b.merged.data());
    accumulate(0, 0, n, b.merged.data());
    return b.merged;
  }
  if (static_cast<int>(b.perThread.size()) < threads) b.perThread.resize(threads);
  b.touched.resize(b.perThread.size());
  int team = 1;
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
#pragma omp single
    team = omp_get_num_threads();  // implicit barrier: every member sees it
    std::vector<double>& buf = b.perThread[t];
    if (buf.size() < size) buf.resize(size);  // (new entries zero, like the rest)
    // thread t's block of the particles (b.blocks, or the static block schedule(static) gives)
    const auto [begin, end] = threadBlock(n, t, team, b.blocks);
    b.touched[t] = accumulate(t, begin, end, buf.data());
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int64_t r = 0; r < runCount; ++r) {
      const std::size_t first = runs[r][0], last = runs[r][0] + runs[r][1];
      double* merged = b.merged.data();
      std::fill(merged + first * C, merged + last * C, 0.0);
      for (int tt = 0; tt < team; ++tt) {  // thread order; a buffer only where it was written
        const std::size_t from = std::max(first, b.touched[tt][0]), to = std::min(last, b.touched[tt][1]);
        const double* add = b.perThread[tt].data();
        for (std::size_t q = from * C; q < to * C; ++q) merged[q] += add[q];
      }
    }  // implicit barrier: no one reads the buffers any more
    std::fill(buf.begin() + static_cast<std::ptrdiff_t>(b.touched[t][0] * C),
              buf.begin() + static_cast<std::ptrdiff_t>(b.touched[t][1] * C), 0.0);
  }
  return b.merged;
}

template <int C, class Values>
const std::vector<double>& depositChannels(const ParticleStencils& s, std::size_t cells, DepositBuffers& b,
                                           Values&& values) {
  return depositChannels<C>(s, cells, b, values,
                            [&s](int, std::size_t begin, std::size_t) { return StencilPiece::of(s, begin); });
}

}  // namespace gf::coupling
