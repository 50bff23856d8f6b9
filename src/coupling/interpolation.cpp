#include "coupling/interpolation.hpp"

#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

/// d(field)/dx_axis at interior cell (i, j, k): central where both neighbours exist (or wrap),
/// one-sided at walls.
double derivative(const GridTopology& t, const Field& f, int i, int j, int k, int axis) {
  int idx[3] = {i, j, k};
  const int n = t.grid.cells[axis];
  const double h = t.grid.spacing[axis];
  int lo[3] = {i, j, k}, hi[3] = {i, j, k};
  double span = 2.0 * h;
  if (t.periodic[axis] || (idx[axis] > 0 && idx[axis] < n - 1)) {
    lo[axis] = t.mapIndex(idx[axis] - 1, axis);
    hi[axis] = t.mapIndex(idx[axis] + 1, axis);
  } else {
    lo[axis] = std::max(idx[axis] - 1, 0);
    hi[axis] = std::min(idx[axis] + 1, n - 1);
    span = (hi[axis] - lo[axis]) * h;
    if (span == 0.0) return 0.0;
  }
  return (f(hi[0], hi[1], hi[2]) - f(lo[0], lo[1], lo[2])) / span;
}

template <class Body>
void forInteriorCells(const GridTopology& t, Body&& body) {
  const auto& n = t.grid.cells;
  forEachIndex(static_cast<std::int64_t>(n[2]) * n[1], n[0], [&](std::int64_t kj) {
    const int k = static_cast<int>(kj / n[1]);
    const int j = static_cast<int>(kj % n[1]);
    for (int i = 0; i < n[0]; ++i) body(i, j, k);
  });
}

}  // namespace

void computeVorticity(const GridTopology& t, const Field* const (&u)[3], Field (&curl)[3]) {
  forInteriorCells(t, [&](int i, int j, int k) {
    curl[0](i, j, k) = derivative(t, *u[2], i, j, k, 1) - derivative(t, *u[1], i, j, k, 2);
    curl[1](i, j, k) = derivative(t, *u[0], i, j, k, 2) - derivative(t, *u[2], i, j, k, 0);
    curl[2](i, j, k) = derivative(t, *u[1], i, j, k, 0) - derivative(t, *u[0], i, j, k, 1);
  });
}

void computeViscousStressDivergence(const GridTopology& t, const Field* const (&u)[3], double viscosity,
                                    Field (&divTau)[3]) {
  double h2[3];
  for (int a = 0; a < 3; ++a) h2[a] = t.grid.spacing[a] * t.grid.spacing[a];
  forInteriorCells(t, [&](int i, int j, int k) {
    const int idx[3] = {i, j, k};
    int lo[3], hi[3];  // neighbour cell along each axis minus this cell (wrapped, or clamped at walls)
    for (int a = 0; a < 3; ++a) {
      lo[a] = (t.periodic[a] ? t.mapIndex(idx[a] - 1, a) : std::max(idx[a] - 1, 0)) - idx[a];
      hi[a] = (t.periodic[a] ? t.mapIndex(idx[a] + 1, a) : std::min(idx[a] + 1, t.grid.cells[a] - 1)) - idx[a];
    }
    for (int c = 0; c < 3; ++c) {
      const Field& f = *u[c];
      const double* d = f.data().data() + f.index(i, j, k);
      const double centre = d[0];
      double lap = 0.0;
      for (int a = 0; a < 3; ++a) {
        const std::ptrdiff_t st = f.stride(a);
        lap += (d[hi[a] * st] - 2.0 * centre + d[lo[a] * st]) / h2[a];
      }
      divTau[c](i, j, k) = viscosity * lap;
    }
  });
}

// The clones: the build uses -ffp-contract=off, so no clone fuses a multiply and an add (the
// same results on every CPU; as GF_VECTOR_CLONES in src/dem/contact/contact_batch.hpp).
#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__) && !defined(__AVX512F__)
#define GF_COUPLING_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define GF_COUPLING_VECTOR_CLONES
#endif

GF_COUPLING_VECTOR_CLONES
void sampleTrilinearBlock(const TrilinearSampler::Location* where, int count, const double* buffer,
                          double (*out)[13]) {
  static_assert(kTrilinearBlockChannels == 10, "channels 0-7 in one vector of 8, 8-9 in one of 2");
  constexpr int kC = kTrilinearBlockChannels;
  using Double8 = double __attribute__((vector_size(64)));
  using Double2 = double __attribute__((vector_size(16)));
  for (int q = 0; q < count; ++q) {
    const TrilinearSampler::Location& l = where[q];
    const double* base = buffer + l.flat * kC;
    const double* frac = l.frac;
    Double8 low{};  // channels 0-7
    Double2 high{};  // channels 8-9
    // the corners, weights and order of sumTrilinearCorners
    for (int dk = 0; dk < 2; ++dk)
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) {
          const double wm =
              (di ? frac[0] : 1.0 - frac[0]) * (dj ? frac[1] : 1.0 - frac[1]) * (dk ? frac[2] : 1.0 - frac[2]);
          const double* v = base + (di * l.step[0] + dj * l.step[1] + dk * l.step[2]) * kC;
          Double8 v8;
          Double2 v2;
          __builtin_memcpy(&v8, v, sizeof v8);
          __builtin_memcpy(&v2, v + 8, sizeof v2);
          low += wm * v8;
          high += wm * v2;
        }
    __builtin_memcpy(out[q], &low, sizeof low);
    __builtin_memcpy(out[q] + 8, &high, sizeof high);
  }
}

}  // namespace gf::coupling
