#pragma once
// Fluid quantities at particle positions, and the cell-centred differential operators the forces
// need (vorticity, viscous stress divergence).
//
// Interpolation modes (key coupling.interpolation):
//   cell       value of the cell containing the particle centre
//   trilinear  trilinear between the 8 surrounding cell centres; in wall directions the position
//              is clamped to the first/last cell centre (constant extrapolation over the half cell
//              next to the wall), in periodic directions indices wrap
//   stencil    sum_c w_pc value_c with the particle's void-fraction stencil (the same weights that
//              distribute the forces: interpolation and distribution are then adjoint)
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "core/grid.hpp"
#include "coupling/axis_offsets.hpp"
#include "coupling/grid_topology.hpp"
#include "coupling/stencil.hpp"

namespace gf::coupling {

enum class InterpolationMode { Cell, Trilinear, Stencil };

/// Trilinear weights: 8 flat indices and weights (sum 1) for point x.
struct TrilinearWeights {
  std::size_t cell[8];
  double weight[8];
};

/// Position of x along axis a in cell-centre units: the lower of the two surrounding cell centres
/// (unmapped index) and the fraction towards the upper one. Clamped to the first/last centre in
/// wall directions (see the file comment).
struct AxisPosition {
  int lower;
  double fraction;
};
inline AxisPosition axisPosition(const GridTopology& t, const Vec3& x, int a) {
  double s = (x[a] - t.grid.origin[a]) * t.inverseSpacing[a] - 0.5;
  if (!t.open(a, 0)) s = std::max(s, 0.0);
  if (!t.open(a, 1)) s = std::min(s, static_cast<double>(t.grid.cells[a] - 1));
  const int f = floorToInt(s);
  return {f, s - f};
}

inline TrilinearWeights trilinearWeights(const GridTopology& t, const Vec3& x) {
  int lo[3], hi[3];
  double frac[3];
  for (int a = 0; a < 3; ++a) {
    const AxisPosition q = axisPosition(t, x, a);
    frac[a] = q.fraction;
    lo[a] = t.mapIndex(q.lower, a);
    hi[a] = t.mapIndex(q.lower + 1, a);
  }
  TrilinearWeights w{};
  int m = 0;
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        w.cell[m] = t.flat(di ? hi[0] : lo[0], dj ? hi[1] : lo[1], dk ? hi[2] : lo[2]);
        w.weight[m] = (di ? frac[0] : 1.0 - frac[0]) * (dj ? frac[1] : 1.0 - frac[1]) * (dk ? frac[2] : 1.0 - frac[2]);
        ++m;
      }
  return w;
}

/// Interpolation weights of one point: computed once per particle, applied to every field.
/// Not copyable (cell/weight may point into the object itself).
struct SampleWeights {
  int count = 0;
  const std::size_t* cell = nullptr;
  const double* weight = nullptr;
  std::size_t localCell[8];
  double localWeight[8];
  SampleWeights() = default;
  SampleWeights(const SampleWeights&) = delete;
  SampleWeights& operator=(const SampleWeights&) = delete;
};

/// Weights of particle p at x for the interpolation mode (resolved at compile time).
template <InterpolationMode Mode>
inline void sampleWeights(const GridTopology& t, const ParticleStencils& s, std::size_t p, const Vec3& x,
                          SampleWeights& w) {
  if constexpr (Mode == InterpolationMode::Cell) {
    const auto c = t.cellOf(x);
    w.count = 1;
    w.localCell[0] = t.flat(c[0], c[1], c[2]);
    w.localWeight[0] = 1.0;
    w.cell = w.localCell;
    w.weight = w.localWeight;
  } else if constexpr (Mode == InterpolationMode::Trilinear) {
    const TrilinearWeights tw = trilinearWeights(t, x);
    w.count = 8;
    for (int m = 0; m < 8; ++m) {
      w.localCell[m] = tw.cell[m];
      w.localWeight[m] = tw.weight[m];
    }
    w.cell = w.localCell;
    w.weight = w.localWeight;
  } else {
    w.count = s.count[p];
    w.cell = s.cell.data() + p * s.capacity;
    w.weight = s.weight.data() + p * s.capacity;
  }
}

/// out[i] = sum_m w_m fields[i][cell_m].
template <int N>
inline void sampleFields(const SampleWeights& w, const Field* const (&fields)[N], double (&out)[N]) {
  for (int i = 0; i < N; ++i) out[i] = 0.0;
  for (int m = 0; m < w.count; ++m)
    for (int i = 0; i < N; ++i) out[i] += w.weight[m] * fields[i]->data()[w.cell[m]];
}

/// out[ch] = sum_m w_m buffer[cell_m * channels + ch] for a channel-interleaved cell buffer (all
/// fields a particle needs side by side: one cache line per stencil entry).
/// Channels > 0: the channel count known at compile time (the sums stay in registers), same
/// operations in the same order as the run-time count (Channels = 0).
template <int Channels = 0>
inline void sampleInterleaved(const SampleWeights& w, const double* buffer, int channels, double* out) {
  if constexpr (Channels > 0) channels = Channels;
  double sum[Channels > 0 ? Channels : 1];
  double* acc = Channels > 0 ? sum : out;
  for (int ch = 0; ch < channels; ++ch) acc[ch] = 0.0;
  for (int m = 0; m < w.count; ++m) {
    const double* v = buffer + w.cell[m] * channels;
    const double wm = w.weight[m];
    for (int ch = 0; ch < channels; ++ch) acc[ch] += wm * v[ch];
  }
  if constexpr (Channels > 0)
    for (int ch = 0; ch < Channels; ++ch) out[ch] = sum[ch];
}

/// The trilinear sum over the 8 cells of a located point: the lower cell's channels at base, the
/// upper cells at the flat offsets step[a] (in cells), weights from the fractions frac[a], in the
/// order of trilinearWeights (bit-identical to sampleInterleaved over its weights).
template <int Channels>
inline void sumTrilinearCorners(const double* base, const std::ptrdiff_t* step, const double* frac, int channels,
                                double* out) {
  double sum[Channels > 0 ? Channels : 1];
  double* acc = Channels > 0 ? sum : out;
  for (int ch = 0; ch < channels; ++ch) acc[ch] = 0.0;
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        const double wm =
            (di ? frac[0] : 1.0 - frac[0]) * (dj ? frac[1] : 1.0 - frac[1]) * (dk ? frac[2] : 1.0 - frac[2]);
        const double* v = base + (di * step[0] + dj * step[1] + dk * step[2]) * channels;
        for (int ch = 0; ch < channels; ++ch) acc[ch] += wm * v[ch];
      }
  if constexpr (Channels > 0)
    for (int ch = 0; ch < Channels; ++ch) out[ch] = sum[ch];
}

/// Trilinear interpolation of a channel-interleaved cell buffer at x, without building the weight
/// arrays: the same cells, weights and sums in the same order as trilinearWeights followed by
/// sampleInterleaved (bit-identical), with the 8 cells as base + axis offsets.
template <int Channels = 0>
inline void sampleTrilinear(const GridTopology& t, const Vec3& x, const double* buffer, int channels, double* out) {
  if constexpr (Channels > 0) channels = Channels;
  int lo[3];
  std::ptrdiff_t step[3];  // flat offset of the upper cell along each axis (0 where folded onto lo)
  double frac[3];
  const std::ptrdiff_t stride[3] = {1, t.grid.cells[0] + 2 * t.grid.ghosts,
                                    static_cast<std::ptrdiff_t>(t.grid.cells[0] + 2 * t.grid.ghosts) *
                                        (t.grid.cells[1] + 2 * t.grid.ghosts)};
  for (int a = 0; a < 3; ++a) {
    const AxisPosition q = axisPosition(t, x, a);
    frac[a] = q.fraction;
    lo[a] = t.mapIndex(q.lower, a);
    step[a] = (t.mapIndex(q.lower + 1, a) - lo[a]) * stride[a];
  }
  const double* base = buffer + t.flat(lo[0], lo[1], lo[2]) * channels;
  sumTrilinearCorners<Channels>(base, step, frac, channels, out);
}

/// sampleTrilinear with what depends only on the grid resolved once per particle loop: the clamp
/// bounds of each axis (walls: first and last centre; periodic: none) and the flat offsets of the
/// cell indices a particle can reach (mapIndex times the axis stride, tabulated). The same cells,
/// weights and sums in the same order as sampleTrilinear (bit-identical), without the branches on
/// the periodicity, the clamp and the wall fold (hard to predict where many particles sit in the
/// half cell next to a wall).
class TrilinearSampler {
 public:
  explicit TrilinearSampler(const GridTopology& t) : t_(&t) {
    const std::ptrdiff_t stride[3] = {1, t.grid.cells[0] + 2 * t.grid.ghosts,
                                      static_cast<std::ptrdiff_t>(t.grid.cells[0] + 2 * t.grid.ghosts) *
                                          (t.grid.cells[1] + 2 * t.grid.ghosts)};
    shift_ = static_cast<std::ptrdiff_t>(t.flat(0, 0, 0));
    for (int a = 0; a < 3; ++a) {
      Axis& x = axis_[a];
      x.origin = t.grid.origin[a];
      x.inverseSpacing = t.inverseSpacing[a];
      const int n = t.grid.cells[a];
      // std::min(std::max(s, low), high) is s itself for the infinite bounds of a periodic axis
      x.low = t.open(a, 0) ? -std::numeric_limits<double>::infinity() : 0.0;
      x.high = t.open(a, 1) ? std::numeric_limits<double>::infinity() : static_cast<double>(n - 1);
      x.cells = AxisOffsetTable<std::ptrdiff_t>(t, a, stride[a]);
    }
  }

  /// Where a point samples: the flat index of its lower cell, the flat offsets of the upper
  /// cells along each axis (0 where folded onto the lower one) and the fractions.
  struct Location {
    std::ptrdiff_t flat;
    std::ptrdiff_t step[3];
    double frac[3];
  };

  /// (Written field by field into l: a Location returned by value was built on the stack and
  /// copied with wider loads than its stores, which stalled store forwarding.)
  void locate(const Vec3& position, Location& l) const {
    std::ptrdiff_t flat = shift_;
    for (int a = 0; a < 3; ++a) {
      const Axis& x = axis_[a];
      // as axisPosition: scaled coordinate, clamped in wall directions, floor and fraction
      const double s = std::min(std::max((position[a] - x.origin) * x.inverseSpacing - 0.5, x.low), x.high);
      const int lower = floorToInt(s);
      l.frac[a] = s - lower;
      std::ptrdiff_t lo, hi;
      x.cells.pair(*t_, lower, lo, hi);
      flat += lo;
      l.step[a] = hi - lo;
    }
    l.flat = flat;
  }

  /// The weighted sums of the channels at a located point. Locating a block of points first and
  /// then summing lets the latency chains of several points overlap.
  template <int Channels = 0>
  void sampleAt(const Location& l, const double* buffer, int channels, double* out) const {
    if constexpr (Channels > 0) channels = Channels;
    const double* base = buffer + l.flat * channels;
    const double* frac = l.frac;
    const std::ptrdiff_t* step = l.step;
    sumTrilinearCorners<Channels>(base, step, frac, channels, out);
  }

  template <int Channels = 0>
  void sample(const Vec3& position, const double* buffer, int channels, double* out) const {
    Location l;
    locate(position, l);
    sampleAt<Channels>(l, buffer, channels, out);
  }

 private:
  struct Axis {
    double origin = 0.0, inverseSpacing = 1.0, low = 0.0, high = 0.0;
    AxisOffsetTable<std::ptrdiff_t> cells;  // offsets of the cell indices along the axis
  };
  const GridTopology* t_;
  std::ptrdiff_t shift_ = 0;  // flat(0, 0, 0)
  Axis axis_[3];
};

/// The channels of the force pass's standard layout (u, eps, grad p, div tau) at `count` located
/// points: out[q][ch] = TrilinearSampler::sampleAt<kTrilinearBlockChannels> at where[q], bit for
/// bit (the same products and sums per channel, several channels per vector instruction; compiled
/// also for AVX2 and AVX-512 and picked at run time, interpolation.cpp).
inline constexpr int kTrilinearBlockChannels = 10;
void sampleTrilinearBlock(const TrilinearSampler::Location* where, int count, const double* buffer,
                          double (*out)[13]);

/// One-off sample of several fields at particle p (tests, diagnostics).
template <InterpolationMode Mode, int N>
inline void sampleAt(const GridTopology& t, const ParticleStencils& s, std::size_t p, const Vec3& x,
                     const Field* const (&fields)[N], double (&out)[N]) {
  SampleWeights w;
  sampleWeights<Mode>(t, s, p, x, w);
  sampleFields<N>(w, fields, out);
}

/// Vorticity omega = curl u of a cell-centred velocity (central differences; one-sided next to
/// walls, wrapped across periodic boundaries). Writes interior cells of `curl`.
void computeVorticity(const GridTopology& t, const Field* const (&velocity)[3], Field (&curl)[3]);

/// Divergence of the viscous stress of an incompressible Newtonian fluid, mu laplace(u), by the
/// 7-point Laplacian (zero normal gradient at walls, wrapped at periodic boundaries). Supply the
/// fluid solver's own div(tau) through FluidView where it has one.
void computeViscousStressDivergence(const GridTopology& t, const Field* const (&velocity)[3], double viscosity,
                                    Field (&divTau)[3]);

}  // namespace gf::coupling
