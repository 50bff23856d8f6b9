#include "fluid/multigrid.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <omp.h>

#include "core/reduction.hpp"
#include "fluid/double2.hpp"
#include "fluid/loops.hpp"

namespace gf::fluid {

namespace {
constexpr int kPreSmooth = 2;
constexpr int kPostSmooth = 2;
constexpr std::size_t kCoarsestCells = 64;
constexpr std::size_t kDenseCells = 256;  // coarsest levels up to this size are solved directly
constexpr int kCoarsestSweeps = 40;
// Multigrid levels are threaded from this many grid lines (a 32^3 level: 1024 lines, about 30 us
// per half-sweep, enough to pay for a parallel region; the fluid loops' default is 2048).
constexpr std::int64_t kLevelSerialBelow = 512;
// Teams of the pressure solve: grids below kSerialCellsBelow cells, members own at least this many fine cells.
constexpr std::int64_t kTeamCellsPerThread = 1500;
}  // namespace

void MultigridPoisson::setup(const std::array<int, 3>& n, const std::array<bool, 3>& periodic,
                             const std::array<std::vector<double>, 3>& T, const std::array<bool, 6>& dirichlet) {
  singular_ = true;
  for (bool d : dirichlet) singular_ = singular_ && !d;
  // Levels are rebuilt in place (the coupled solver calls setup every step): vectors keep their
  // capacity, so a repeated setup on the same grid allocates nothing.
  factors_.clear();
  if (levels_.empty()) levels_.emplace_back();
  // Axis order: the longest axis first (ties keep the caller's order).
  perm_ = {0, 1, 2};
  int longest = 0;
  for (int a = 1; a < 3; ++a)
    if (n[a] > n[longest]) longest = a;
  if (longest != 0) perm_ = {longest, 0, longest == 1 ? 2 : 1};
  PoissonLevel& fine = levels_[0];
  std::array<bool, 6> dir = dirichlet;
  for (int q = 0; q < 3; ++q) {
    fine.n[q] = n[perm_[q]];
    fine.periodic[q] = periodic[perm_[q]];
    dir[2 * q] = dirichlet[2 * perm_[q]];
    dir[2 * q + 1] = dirichlet[2 * perm_[q] + 1];
  }
  dirichlet_ = dir;
  // Caller index of internal (i0, i1, i2): caller coordinate perm_[q] is i_q, so the index is the
  // sum over q of i_q times the caller's stride of axis perm_[q] (in the array of that face axis).
  auto callerStrides = [&](int faceAxis) {
    const std::size_t ex = n[0] + (faceAxis == 0), ey = n[1] + (faceAxis == 1);
    const std::size_t caller[3] = {1, ex, ex * ey};
    return std::array<std::size_t, 3>{caller[perm_[0]], caller[perm_[1]], caller[perm_[2]]};
  };
  // body(internal, caller) for the points of internal planes [k0, k1) of an array of pts points.
  auto gather = [&](const std::array<int, 3>& pts, const std::array<std::size_t, 3>& st, int k0, int k1, auto&& body) {
    std::size_t internal = static_cast<std::size_t>(k0) * pts[0] * pts[1];
    for (int k = k0; k < k1; ++k)
      for (int j = 0; j < pts[1]; ++j) {
        const std::size_t base = st[1] * static_cast<std::size_t>(j) + st[2] * static_cast<std::size_t>(k);
        for (int i = 0; i < pts[0]; ++i) body(internal++, base + st[0] * static_cast<std::size_t>(i));
      }
  };
  if (longest == 0) {
    callerCell_.clear();
  } else if (callerCell_.size() != fine.cells() || callerN_ != n) {  // depends on the grid only
    callerCell_.resize(fine.cells());
    gather(fine.n, callerStrides(-1), 0, fine.n[2], [&](std::size_t c, std::size_t e) { callerCell_[c] = e; });
  }
  callerN_ = n;
  // Level shapes first (they depend on the grid only), then the coefficients.
  for (int q = 0; q < 3; ++q) {
    std::array<int, 3> fn = fine.n;
    fn[q] += 1;
    fine.T[q].resize(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2]);  // every face copied below
  }
  std::size_t count = 1;
  while (levels_[count - 1].cells() > kCoarsestCells) {
    // Coarsen by 2 every axis with more than 1 cell (odd counts: the last coarse cell covers one
    // fine cell; a 2-cell axis, the depth of a pseudo-2D bed, goes to 1: kept at 2 its coupling
    // would grow 4x per level relative to the others and point smoothing would stall -- twice the
    // CG iterations on 2 x 30 x 90).
    std::array<int, 3> f{1, 1, 1};
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      if (levels_[count - 1].n[a] > 1) {
        f[a] = 2;
        any = true;
      }
    }
    if (!any) break;
    if (levels_.size() <= count) levels_.emplace_back();
    coarsenShape(levels_[count - 1], levels_[count], f);
    factors_.push_back(f);
    ++count;
  }
  levels_.resize(count);
  PoissonLevel& F = levels_[0];  // (levels_ may have grown)
  // Work arrays: every entry is written before it is read (solve, vcycle), so they are only
  // sized (a setup per step on the same grid writes nothing here).
  for (auto& L : levels_) {
    allocateDiagonal(L);
    L.x.resize(L.cells());
    L.b.resize(L.cells());
  }
  const std::size_t N = F.cells();
  for (auto* v : {&xInternal_, &bInternal_, &p_, &q_}) v->resize(N);
  // The fine coefficients (copied into the internal axis order), the fine diagonal, level 1's
  // coefficients and diagonal: split by planes on a small grid's team (setupTeam_ times it
  // against one thread), one value per thread and entry: the same values for any team size.
  const bool twoLevels = count >= 2;
  int team = 1;
  const bool tuned = twoLevels && gf::threadCount() > 1 && static_cast<std::int64_t>(N) < kSerialCellsBelow;
  if (tuned) {
    const int maxTeam = static_cast<int>(std::min<std::int64_t>(
        {gf::threadCount(), F.n[2], levels_[1].n[2], std::max<std::int64_t>(1, static_cast<std::int64_t>(N) / kTeamCellsPerThread)}));
    team = setupTeam_.pick(maxTeam);
  }
  const double started = TeamTuner::now();
  const bool threaded = team == 1 && !serialLoops();  // one thread: loops may still start teams (large grids)
  auto member = [&](int t, int members) {
    auto planes = [&](int nz, int extra) {  // [k0, k1) of nz planes (+ extra face plane for the last)
      return std::pair<int, int>{nz * t / members, nz * (t + 1) / members + (t == members - 1 ? extra : 0)};
    };
    auto diagonalOfPlanes = [&](PoissonLevel& L) {  // the diagonal of this member's planes of L
      const auto [k0, k1] = planes(L.n[2], 0);
      const auto lineBegin = static_cast<std::int64_t>(L.n[1]) * k0, lineEnd = static_cast<std::int64_t>(L.n[1]) * k1;
      if (threaded) {
        parallelFor(lineEnd - lineBegin, [&](std::int64_t l) { diagonalLines(L, dirichlet_, lineBegin + l, lineBegin + l + 1); });
      } else {
        diagonalLines(L, dirichlet_, lineBegin, lineEnd);
      }
    };
    for (int q = 0; q < 3; ++q) {
      const auto [k0, k1] = planes(F.n[2], q == 2 ? 1 : 0);
      std::array<int, 3> fn = F.n;
      fn[q] += 1;
      const double* src = T[perm_[q]].data();
      double* dst = F.T[q].data();
      if (longest == 0) {
        const std::size_t plane = static_cast<std::size_t>(fn[0]) * fn[1];
        std::copy(src + plane * k0, src + plane * k1, dst + plane * k0);
      } else {
        gather(fn, callerStrides(perm_[q]), k0, k1, [&](std::size_t c, std::size_t e) { dst[c] = src[e]; });
      }
    }
#pragma omp barrier
    diagonalOfPlanes(F);
    if (twoLevels) {
      PoissonLevel& C = levels_[1];
      for (int a = 0; a < 3; ++a) {
        const auto [k0, k1] = planes(C.n[2], a == 2 ? 1 : 0);
        std::array<int, 3> fn = C.n;
        fn[a] += 1;
        const auto lineBegin = static_cast<std::int64_t>(fn[1]) * k0, lineEnd = static_cast<std::int64_t>(fn[1]) * k1;
        if (threaded) {
          parallelFor(lineEnd - lineBegin, [&](std::int64_t l) {
            coarsenLines(F, C, factors_[0], a, lineBegin + l, lineBegin + l + 1);
          });
        } else {
          coarsenLines(F, C, factors_[0], a, lineBegin, lineEnd);
        }
      }
#pragma omp barrier
      diagonalOfPlanes(C);
    }
  };
  if (team > 1) {
#pragma omp parallel num_threads(team)
    member(omp_get_thread_num(), omp_get_num_threads());
  } else {
    member(0, 1);
  }
  if (tuned) setupTeam_.record(team, TeamTuner::now() - started);  // (both choices: the warm-up needs both)
  classifyLevel(F);
  if (twoLevels) classifyLevel(levels_[1]);
  for (std::size_t l = 2; l < count; ++l) {  // small levels
    coarsen(levels_[l - 1], levels_[l], factors_[l - 1]);
    buildDiagonal(levels_[l], dirichlet_);
  }
  factorCoarsest();
  activeCells_ = 0.0;  // a count: exact in any order
  for (double v : F.invDiag) activeCells_ += v > 0.0 ? 1.0 : 0.0;
  zeros_.assign(static_cast<std::size_t>(F.n[0]) + 1, 0.0);
}

namespace {
/// Calls fn(neighbourCell, T) for each coupled neighbour of cell (i, j, k) on level L.
template <class Fn>
void forEachNeighbour(const PoissonLevel& L, int i, int j, int k, Fn&& fn) {
  const int idx[3] = {i, j, k};
  for (int a = 0; a < 3; ++a) {
    if (L.n[a] == 1) continue;
    int hi[3] = {i, j, k};
    hi[a] += 1;
    const double tl = L.T[a][L.faceIndex(a, i, j, k)];
    const double th = L.T[a][L.faceIndex(a, hi[0], hi[1], hi[2])];
    int m[3] = {i, j, k}, p[3] = {i, j, k};
    bool hasM = true, hasP = true;
    if (idx[a] > 0) m[a] -= 1;
    else if (L.periodic[a]) m[a] = L.n[a] - 1;
    else hasM = false;
    if (idx[a] < L.n[a] - 1) p[a] += 1;
    else if (L.periodic[a]) p[a] = 0;
    else hasP = false;
    const auto cell = [&](const int* c) {
      return static_cast<std::size_t>(c[0]) + static_cast<std::size_t>(L.n[0]) * (c[1] + static_cast<std::size_t>(L.n[1]) * c[2]);
    };
    if (hasM) fn(cell(m), tl);
    if (hasP) fn(cell(p), th);
  }
}
}  // namespace

void MultigridPoisson::factorCoarsest() {
  // Dense Cholesky factor of the coarsest operator (A + alpha 1 1^T over the active cells when the
  // problem is singular: its solution of a compatible right-hand side is the zero-mean solution of
  // A). Falls back to Gauss-Seidel sweeps if the level is too large or not positive definite
  // (e.g. a fluid region cut off by blocked cells).
  const PoissonLevel& L = levels_.back();
  const std::size_t N = L.cells();
  coarseCholesky_.clear();
  if (N > kDenseCells) return;
  std::vector<double>& M = coarseCholesky_;
  M.assign(N * N, 0.0);
  double diagSum = 0.0, active = 0.0;
  for (int k = 0; k < L.n[2]; ++k)
    for (int j = 0; j < L.n[1]; ++j)
      for (int i = 0; i < L.n[0]; ++i) {
        const std::size_t c = static_cast<std::size_t>(i) + static_cast<std::size_t>(L.n[0]) * (j + static_cast<std::size_t>(L.n[1]) * k);
        if (L.diag[c] <= 0.0) {
          M[c * N + c] = 1.0;  // isolated cell: x = 0 (its b is 0)
          continue;
        }
        M[c * N + c] += L.diag[c];
        diagSum += L.diag[c];
        active += 1.0;
        forEachNeighbour(L, i, j, k, [&](std::size_t nb, double t) { M[c * N + nb] -= t; });
      }
  if (singular_ && active > 0.0) {
    const double alpha = diagSum / (active * active);
    for (std::size_t r = 0; r < N; ++r)
      for (std::size_t c = 0; c < N; ++c)
        if (L.diag[r] > 0.0 && L.diag[c] > 0.0) M[r * N + c] += alpha;
  }
  // In-place Cholesky, lower triangle (row-major).
  for (std::size_t c = 0; c < N; ++c) {
    double d = M[c * N + c];
    for (std::size_t q = 0; q < c; ++q) d -= M[c * N + q] * M[c * N + q];
    if (!(d > 1e-12 * std::abs(M[c * N + c]))) {
      coarseCholesky_.clear();
      return;
    }
    d = std::sqrt(d);
    M[c * N + c] = d;
    for (std::size_t r = c + 1; r < N; ++r) {
      double v = M[r * N + c];
      for (std::size_t q = 0; q < c; ++q) v -= M[r * N + q] * M[c * N + q];
      M[r * N + c] = v / d;
    }
  }
}

void MultigridPoisson::solveCoarsest(PoissonLevel& L) const {
  const std::size_t N = L.cells();
  const double* M = coarseCholesky_.data();
  double* x = L.x.data();
  for (std::size_t r = 0; r < N; ++r) {  // L y = b
    double v = L.b[r];
    for (std::size_t q = 0; q < r; ++q) v -= M[r * N + q] * x[q];
    x[r] = v / M[r * N + r];
  }
  for (std::size_t r = N; r-- > 0;) {  // L^T x = y
    double v = x[r];
    for (std::size_t q = r + 1; q < N; ++q) v -= M[q * N + r] * x[q];
    x[r] = v / M[r * N + r];
  }
  for (std::size_t c = 0; c < N; ++c)
    if (L.diag[c] <= 0.0) x[c] = 0.0;
}

void MultigridPoisson::buildDiagonal(PoissonLevel& L, const std::array<bool, 6>& dirichlet) const {
  classifyLevel(L);
  allocateDiagonal(L);
  const auto lines = static_cast<std::int64_t>(L.n[1]) * L.n[2];
  if (lines < kSerialBelow || serialLoops()) {
    diagonalLines(L, dirichlet, 0, lines);
  } else {
    parallelFor(lines, [&](std::int64_t line) { diagonalLines(L, dirichlet, line, line + 1); });
  }
}

void MultigridPoisson::classifyLevel(PoissonLevel& L) {
  // Constant coefficients? (faces between two cells, wrap-around faces of periodic axes included)
  L.constantT = true;
  for (int a = 0; a < 3 && L.constantT; ++a) {
    L.tConstant[a] = 0.0;
    if (L.n[a] == 1) continue;  // no coupling along a
    bool first = true;
    for (int k = 0; k < L.n[2] + (a == 2) && L.constantT; ++k)
      for (int j = 0; j < L.n[1] + (a == 1); ++j)
        for (int i = 0; i < L.n[0] + (a == 0); ++i) {
          const int idx[3] = {i, j, k};
          if (!L.periodic[a] && (idx[a] == 0 || idx[a] == L.n[a])) continue;  // boundary faces
          const double t = L.T[a][L.faceIndex(a, i, j, k)];
          if (first) {
            L.tConstant[a] = t;
            first = false;
          } else if (t != L.tConstant[a]) {
            L.constantT = false;
            break;
          }
        }
  }
  L.redBlackSafe = true;
  for (int a = 0; a < 3; ++a)
    if (L.periodic[a] && L.n[a] % 2 == 1) L.redBlackSafe = false;
}

void MultigridPoisson::allocateDiagonal(PoissonLevel& L) {
  // Every entry is written by diagonalLines: sized, not cleared.
  L.invDiag.resize(L.cells());
  L.diag.resize(L.cells());
}

void MultigridPoisson::diagonalLines(PoissonLevel& L, const std::array<bool, 6>& dirichlet, std::int64_t lineBegin,
                                     std::int64_t lineEnd) {
  const int nx = L.n[0], ny = L.n[1];
  for (std::int64_t line = lineBegin; line < lineEnd; ++line) {
    const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
    for (int i = 0; i < nx; ++i) {
      const int idx[3] = {i, j, k};
      double d = 0.0;
      for (int a = 0; a < 3; ++a) {
        int lo[3] = {i, j, k}, hi[3] = {i, j, k};
        hi[a] += 1;
        const double tl = L.T[a][L.faceIndex(a, lo[0], lo[1], lo[2])];
        const double th = L.T[a][L.faceIndex(a, hi[0], hi[1], hi[2])];
        const bool lowBoundary = idx[a] == 0, highBoundary = idx[a] == L.n[a] - 1;
        if (L.n[a] == 1 && L.periodic[a]) continue;  // one periodic cell couples to itself only
        d += (!lowBoundary || L.periodic[a]) ? tl : (dirichlet[2 * a] ? 2.0 * tl : 0.0);
        d += (!highBoundary || L.periodic[a]) ? th : (dirichlet[2 * a + 1] ? 2.0 * th : 0.0);
      }
      L.invDiag[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * line] = d > 0.0 ? 1.0 / d : 0.0;
      L.diag[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * line] = d;
    }
  }
}

void MultigridPoisson::coarsen(const PoissonLevel& fine, PoissonLevel& coarse, const std::array<int, 3>& f) const {
  coarsenShape(fine, coarse, f);
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = coarse.n;
    fn[a] += 1;
    const auto lines = static_cast<std::int64_t>(fn[1]) * fn[2];
    if (lines < kSerialBelow || serialLoops()) {
      coarsenLines(fine, coarse, f, a, 0, lines);
    } else {
      parallelFor(lines, [&](std::int64_t line) { coarsenLines(fine, coarse, f, a, line, line + 1); });
    }
  }
}

void MultigridPoisson::coarsenShape(const PoissonLevel& fine, PoissonLevel& coarse, const std::array<int, 3>& f) {
  for (int a = 0; a < 3; ++a) coarse.n[a] = (fine.n[a] + f[a] - 1) / f[a];
  coarse.periodic = fine.periodic;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = coarse.n;
    fn[a] += 1;
    coarse.T[a].resize(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2]);  // every face written by coarsenLines
  }
}

void MultigridPoisson::coarsenLines(const PoissonLevel& fine, PoissonLevel& coarse, const std::array<int, 3>& f, int a,
                                    std::int64_t lineBegin, std::int64_t lineEnd) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  std::array<int, 3> fn = coarse.n;
  fn[a] += 1;
  // Rediscretisation: divide by the coarse centre distance in fine cells, (size of the block
  // below + size above) / 2, or the adjacent block's size at a non-periodic boundary face (there
  // the operator doubles T: half a block to the boundary). 2 everywhere for even counts; odd
  // counts leave a last block of 1 cell. One value per coarse face position along a.
  const int nc = coarse.n[a], nf = fine.n[a];
  std::vector<double> distance(static_cast<std::size_t>(nc) + 1, 1.0);
  if (f[a] == 2)
    for (int C = 0; C <= nc; ++C) {
      auto blockSize = [&](int I) { return std::min(2, nf - 2 * I); };
      const int below = C > 0 ? C - 1 : (fine.periodic[a] ? nc - 1 : -1);
      const int above = C < nc ? C : (fine.periodic[a] ? 0 : -1);
      if (below >= 0 && above >= 0) distance[static_cast<std::size_t>(C)] = 0.5 * (blockSize(below) + blockSize(above));
      else distance[static_cast<std::size_t>(C)] = blockSize(below >= 0 ? below : above);
    }
  // Fine face array of axis a: strides per axis.
  const std::size_t fx = static_cast<std::size_t>(fine.n[0]) + (a == 0), fy = static_cast<std::size_t>(fine.n[1]) + (a == 1);
  const std::size_t fineStride[3] = {1, fx, fx * fy};
  const double* T = fine.T[a].data();
  for (std::int64_t line = lineBegin; line < lineEnd; ++line) {
    const int J = static_cast<int>(line % fn[1]), K = static_cast<int>(line / fn[1]);
    double* out = coarse.T[a].data() + static_cast<std::size_t>(fn[0]) * static_cast<std::size_t>(line);
    for (int I = 0; I < fn[0]; ++I) {
      const int C[3] = {I, J, K};
      int F[3];
      F[a] = std::min(C[a] * f[a], fine.n[a]);  // last face of an odd axis: the boundary face
      F[b] = C[b] * f[b];
      F[c] = C[c] * f[c];
      // Children inside the fine grid (odd axis: one child only), summed in (db, dc) order.
      const int nb = std::min(f[b], fine.n[b] - F[b]), ncc = std::min(f[c], fine.n[c] - F[c]);
      const std::size_t base = F[0] * fineStride[0] + F[1] * fineStride[1] + F[2] * fineStride[2];
      double sum = 0.0;
      for (int db = 0; db < nb; ++db)
        for (int dc = 0; dc < ncc; ++dc) sum += T[base + db * fineStride[b] + dc * fineStride[c]];
      out[I] = sum / distance[static_cast<std::size_t>(C[a])];
    }
  }
}

namespace {

/// Neighbour coefficients and offsets of one grid line in y and z; a missing neighbour gets a
/// zero coefficient line and offset 0, so the inner loops need no branches.
struct LineStencil {
  const double* tS;
  const double* tN;
  const double* tB;
  const double* tT;
  std::ptrdiff_t oS, oN, oB, oT;
};

LineStencil lineStencil(const PoissonLevel& L, int j, int k, const double* zeros) {
  const int ny = L.n[1], nz = L.n[2];
  const auto sy = static_cast<std::ptrdiff_t>(L.n[0]), sz = static_cast<std::ptrdiff_t>(L.n[0]) * ny;
  const bool hasS = j > 0 || (L.periodic[1] && ny > 1), hasN = j < ny - 1 || (L.periodic[1] && ny > 1);
  const bool hasB = k > 0 || (L.periodic[2] && nz > 1), hasT = k < nz - 1 || (L.periodic[2] && nz > 1);
  LineStencil st;
  st.tS = hasS ? L.T[1].data() + L.faceIndex(1, 0, j, k) : zeros;
  st.tN = hasN ? L.T[1].data() + L.faceIndex(1, 0, j + 1, k) : zeros;
  st.tB = hasB ? L.T[2].data() + L.faceIndex(2, 0, j, k) : zeros;
  st.tT = hasT ? L.T[2].data() + L.faceIndex(2, 0, j, k + 1) : zeros;
  st.oS = !hasS ? 0 : (j > 0 ? -sy : (ny - 1) * sy);
  st.oN = !hasN ? 0 : (j < ny - 1 ? sy : -(ny - 1) * sy);
  st.oB = !hasB ? 0 : (k > 0 ? -sz : (nz - 1) * sz);
  st.oT = !hasT ? 0 : (k < nz - 1 ? sz : -(nz - 1) * sz);
  return st;
}

}  // namespace

namespace {
/// y = A x on grid line (j, k) of level L (x: the whole level, y: the line).
/// Coefficients of one grid line: the level's arrays, or (CONSTANT) the level's constant per axis
/// (0 for a missing neighbour line): the same values, so the same results, without the reads.
template <bool CONSTANT>
struct LineCoefficients {
  const double* tS;
  const double* tN;
  const double* tB;
  const double* tT;
  const double* tx;
  double cS = 0.0, cN = 0.0, cB = 0.0, cT = 0.0, cx = 0.0;
  [[gnu::always_inline]] LineCoefficients(const PoissonLevel& L, const LineStencil& st, int j, int k,
                                          const double* zeros)
      : tS(st.tS), tN(st.tN), tB(st.tB), tT(st.tT), tx(L.T[0].data() + L.faceIndex(0, 0, j, k)) {
    if constexpr (CONSTANT) {
      cS = st.tS == zeros ? 0.0 : L.tConstant[1];
      cN = st.tN == zeros ? 0.0 : L.tConstant[1];
      cB = st.tB == zeros ? 0.0 : L.tConstant[2];
      cT = st.tT == zeros ? 0.0 : L.tConstant[2];
      cx = L.tConstant[0];
    }
  }
  double S(int i) const { return CONSTANT ? cS : tS[i]; }
  double N(int i) const { return CONSTANT ? cN : tN[i]; }
  double B(int i) const { return CONSTANT ? cB : tB[i]; }
  double T(int i) const { return CONSTANT ? cT : tT[i]; }
  /// x face i of the line (between cells i-1 and i); only read where it couples two cells.
  double X(int i) const { return CONSTANT ? cx : tx[i]; }
};

/// Y neighbours present on a line: bit 0 south, bit 1 north. A missing one has a zero coefficient
/// line, whose product 0 x adds nothing: the Y < 3 variants skip its two loads and two flops (a
/// 2-cell y axis, the depth of a pseudo-2D bed, has one y neighbour per cell; a 1-cell one none).
inline int yNeighbours(const LineStencil& st, const double* zeros) {
  return (st.tS != zeros ? 1 : 0) | (st.tN != zeros ? 2 : 0);
}

/// S x_S + N x_N + B x_B + T x_T of cell i (the present y neighbours only, in that order).
template <int Y, class Coefficients>
[[gnu::always_inline]] inline double yzTerms(const Coefficients& t, const LineStencil& st, const double* x, int i) {
  if constexpr (Y == 3) {
    return t.S(i) * x[i + st.oS] + t.N(i) * x[i + st.oN] + t.B(i) * x[i + st.oB] + t.T(i) * x[i + st.oT];
  } else if constexpr (Y == 1) {
    return t.S(i) * x[i + st.oS] + t.B(i) * x[i + st.oB] + t.T(i) * x[i + st.oT];
  } else if constexpr (Y == 2) {
    return t.N(i) * x[i + st.oN] + t.B(i) * x[i + st.oB] + t.T(i) * x[i + st.oT];
  } else {
    return t.B(i) * x[i + st.oB] + t.T(i) * x[i + st.oT];
  }
}

/// Calls fn(std::integral_constant<int, Y>) for the run-time y-neighbour set.
template <class Fn>
inline void dispatchY(int y, Fn&& fn) {
  switch (y) {
    case 3: fn(std::integral_constant<int, 3>{}); break;
    case 2: fn(std::integral_constant<int, 2>{}); break;
    case 1: fn(std::integral_constant<int, 1>{}); break;
    default: fn(std::integral_constant<int, 0>{}); break;
  }
}

template <bool CONSTANT, int Y>
inline void applyLineImpl(const PoissonLevel& L, const double* xv, double* y, int j, int k, const LineStencil& st,
                          const double* zeros) {
  const int nx = L.n[0], ny = L.n[1];
  const std::size_t base = static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k);
  const double* x = xv + base;
  const double* diag = L.diag.data() + base;
  const LineCoefficients<CONSTANT> t(L, st, j, k, zeros);
  const bool perX = L.periodic[0] && nx > 1;
  auto point = [&](int i) {
    const double off = yzTerms<Y>(t, st, x, i) + (i > 0 ? t.X(i) * x[i - 1] : (perX ? t.X(i) * x[nx - 1] : 0.0)) +
                       (i < nx - 1 ? t.X(i + 1) * x[i + 1] : (perX ? t.X(i + 1) * x[0] : 0.0));
    y[i] = diag[i] * x[i] - off;
  };
  int i = 0;
  if constexpr (CONSTANT) {
    // Constant coefficients (e.g. single-phase flow): the cells 1 .. nx - 2 two at a time in the
    // lanes of a two-double vector (fluid/double2.hpp), each lane with the scalar arithmetic of
    // point() (yzTerms in the same order): the same bits.
    if (nx >= 4) {
      point(0);
      const double cx = t.cx;
      for (i = 1; i + 2 <= nx - 1; i += 2) {
        Double2 yz;
        if constexpr (Y == 3)
          yz = t.cS * load2(x + i + st.oS) + t.cN * load2(x + i + st.oN) + t.cB * load2(x + i + st.oB) +
               t.cT * load2(x + i + st.oT);
        else if constexpr (Y == 1)
          yz = t.cS * load2(x + i + st.oS) + t.cB * load2(x + i + st.oB) + t.cT * load2(x + i + st.oT);
        else if constexpr (Y == 2)
          yz = t.cN * load2(x + i + st.oN) + t.cB * load2(x + i + st.oB) + t.cT * load2(x + i + st.oT);
        else
          yz = t.cB * load2(x + i + st.oB) + t.cT * load2(x + i + st.oT);
        const Double2 off = yz + cx * load2(x + i - 1) + cx * load2(x + i + 1);
        store2(y + i, load2(diag + i) * load2(x + i) - off);
      }
    }
  }
  for (; i < nx; ++i) point(i);
}

inline void applyLine(const PoissonLevel& L, const double* xv, double* y, int j, int k, const double* zeros) {
  const LineStencil st = lineStencil(L, j, k, zeros);
  dispatchY(yNeighbours(st, zeros), [&](auto yc) {
    constexpr int Y = decltype(yc)::value;
    if (L.constantT) applyLineImpl<true, Y>(L, xv, y, j, k, st, zeros);
    else applyLineImpl<false, Y>(L, xv, y, j, k, st, zeros);
  });
}
}  // namespace

void MultigridPoisson::applyLevel(const PoissonLevel& L, const std::vector<double>& xv, std::vector<double>& yv) const {
  const int nx = L.n[0], ny = L.n[1], nz = L.n[2];
  parallelForAbove(static_cast<std::int64_t>(ny) * nz, kLevelSerialBelow, [&](std::int64_t line) {
    const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
    applyLine(L, xv.data(), yv.data() + static_cast<std::size_t>(nx) * line, j, k, zeros_.data());
  });
}

namespace {
template <bool CONSTANT, int Y>
[[gnu::always_inline]] inline void relaxLineImpl(PoissonLevel& L, int j, int k, int colour, const LineStencil& st, const double* zeros) {
  const int nx = L.n[0], ny = L.n[1];
  const std::size_t base = static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k);
  double* x = L.x.data() + base;
  const double* b = L.b.data() + base;
  const double* inv = L.invDiag.data() + base;
  const LineCoefficients<CONSTANT> t(L, st, j, k, zeros);
  const bool perX = L.periodic[0] && nx > 1;
  auto yz = [&](int i) { return yzTerms<Y>(t, st, x, i); };
  auto relaxEdge = [&](int i) {
    double s = b[i] + yz(i);
    if (i > 0) s += t.X(i) * x[i - 1];
    else if (perX) s += t.X(i) * x[nx - 1];
    if (i < nx - 1) s += t.X(i + 1) * x[i + 1];
    else if (perX) s += t.X(i + 1) * x[0];
    x[i] = s * inv[i];
  };
  int i = (j + k + colour) & 1;
  if (i == 0) {
    relaxEdge(0);
    i = 2;
  }
  for (; i < nx - 1; i += 2) x[i] = (b[i] + yz(i) + t.X(i) * x[i - 1] + t.X(i + 1) * x[i + 1]) * inv[i];
  if (i == nx - 1) relaxEdge(i);
}
}  // namespace

// Relaxes the cells with (i+j+k) % 2 == colour on grid line (j, k).
void MultigridPoisson::relaxLine(PoissonLevel& L, int j, int k, int colour) const {
  const double* zeros = zeros_.data();
  const LineStencil st = lineStencil(L, j, k, zeros);
  dispatchY(yNeighbours(st, zeros), [&](auto yc) {
    constexpr int Y = decltype(yc)::value;
    if (L.constantT) relaxLineImpl<true, Y>(L, j, k, colour, st, zeros);
    else relaxLineImpl<false, Y>(L, j, k, colour, st, zeros);
  });
}

// One half-sweep of red-black Gauss-Seidel over the cells with (i+j+k) % 2 == colour.
void MultigridPoisson::smoothColour(PoissonLevel& L, int colour) const {
  const int ny = L.n[1];
  parallelForAbove(static_cast<std::int64_t>(ny) * L.n[2], kLevelSerialBelow, [&](std::int64_t line) {
    relaxLine(L, static_cast<int>(line % ny), static_cast<int>(line / ny), colour);
  });
}

// Colour `first` then colour 1 - first in one pass over memory: plane k of the second colour is
// relaxed right after plane k + 1 of the first (all its first-colour neighbours are then new and
// its second-colour neighbours are not coupled to it). Each thread takes a slab of planes; the
// slab's end planes of the second colour depend on the neighbouring slabs and are relaxed after a
// barrier. Every cell sees exactly the values of two separate half-sweeps: identical results, for
// any thread count, with half the memory traffic.
void MultigridPoisson::smoothPair(PoissonLevel& L, int first) const {
  const int ny = L.n[1], nz = L.n[2], second = 1 - first;
  const auto lines = static_cast<std::int64_t>(ny) * nz;
  if (nz < 4) {
    smoothColour(L, first);
    smoothColour(L, second);
    return;
  }
  int slabs = (lines >= kLevelSerialBelow && !serialLoops()) ? gf::threadCount() : 1;
  slabs = std::min(slabs, nz / 2);
  auto plane = [&](int k, int colour) {
    for (int j = 0; j < ny; ++j) relaxLine(L, j, k, colour);
  };
  auto lagged = [&](std::int64_t s) {
    const int k0 = static_cast<int>(nz * s / slabs), k1 = static_cast<int>(nz * (s + 1) / slabs);
    for (int k = k0; k < k1; ++k) {
      plane(k, first);
      if (k - 1 > k0) plane(k - 1, second);
    }
  };
  auto ends = [&](std::int64_t s) {
    const int k0 = static_cast<int>(nz * s / slabs), k1 = static_cast<int>(nz * (s + 1) / slabs);
    plane(k0, second);
    if (k1 - 1 != k0) plane(k1 - 1, second);
  };
  if (slabs == 1) {
    lagged(0);
    ends(0);
  } else {
    // One slab per thread (gf::parallelFor would run so few iterations serially).
#pragma omp parallel for schedule(static)
    for (int q = 0; q < slabs; ++q) lagged(q);
#pragma omp parallel for schedule(static)
    for (int q = 0; q < slabs; ++q) ends(q);
  }
}

// Forward then backward lexicographic Gauss-Seidel (serial; small levels only): symmetric.
void MultigridPoisson::symmetricGaussSeidel(PoissonLevel& L) const {
  const int nx = L.n[0], ny = L.n[1], nz = L.n[2];
  auto relax = [&](int i, int j, int k) {
    const std::size_t c = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(ny) * k);
    double s = L.b[c];
    forEachNeighbour(L, i, j, k, [&](std::size_t n, double t) { s += t * L.x[n]; });
    L.x[c] = s * L.invDiag[c];
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) relax(i, j, k);
  for (int k = nz - 1; k >= 0; --k)
    for (int j = ny - 1; j >= 0; --j)
      for (int i = nx - 1; i >= 0; --i) relax(i, j, k);
}

namespace {
/// Piecewise-constant prolongation of one grid line: x[i] += coarse[i / factor] (factor 1 or 2;
/// no integer division per cell).
inline void prolongLine(double* x, const double* coarse, int nx, int factor) {
  if (factor == 2) {
    int i = 0;
    for (; i + 1 < nx; i += 2) {
      const double c = coarse[i / 2];
      x[i] += c;
      x[i + 1] += c;
    }
    if (i < nx) x[i] += coarse[i / 2];
  } else {
    for (int i = 0; i < nx; ++i) x[i] += coarse[i];
  }
}

/// The first red half-sweep of a V-cycle level, whose initial x is 0, on grid lines [lb, le): the
/// relaxation's arithmetic with all neighbours 0, x = (b + 0) / diag on the cells of colour 0,
/// 0 on the others, with no neighbour reads (the same values, -0 + 0 included).
[[gnu::always_inline]] inline void firstHalfSweepFromZero(PoissonLevel& L, std::int64_t lb, std::int64_t le) {
  const int nx = L.n[0], ny = L.n[1];
  for (std::int64_t line = lb; line < le; ++line) {
    const std::size_t base = static_cast<std::size_t>(nx) * line;
    double* x = L.x.data() + base;
    const double* b = L.b.data() + base;
    const double* inv = L.invDiag.data() + base;
    const int parity = static_cast<int>(line % ny + line / ny) & 1;  // (j + k) % 2
    for (int i = 0; i < nx; ++i) x[i] = ((i + parity) & 1) ? 0.0 : (b[i] + 0.0) * inv[i];
  }
}
}  // namespace

void MultigridPoisson::vcycle(int l) {
  PoissonLevel& L = levels_[l];
  const bool coarsest = l + 1 == static_cast<int>(levels_.size());
  const bool redBlack = !coarsest && L.redBlackSafe;
  if (!redBlack) {
    double* x = L.x.data();
    const auto lines = static_cast<std::int64_t>(L.n[1]) * L.n[2];
    const int nx = L.n[0];
    parallelForAbove(lines, kLevelSerialBelow, [&](std::int64_t line) {
      std::fill(x + nx * line, x + nx * (line + 1), 0.0);  // first touch by the thread that smooths it
    });
  }
  if (coarsest && !coarseCholesky_.empty()) {
    solveCoarsest(L);
    return;
  }
  if (coarsest || !L.redBlackSafe) {
    // Coarsest level (or a level that cannot be red-black coloured): symmetric GS sweeps.
    const int sweeps = coarsest ? kCoarsestSweeps : kPreSmooth;
    for (int s = 0; s < sweeps; ++s) symmetricGaussSeidel(L);
    if (coarsest) return;
  } else {
    // From x = 0: the first red half-sweep without neighbour reads, then black, then the other pairs.
    parallelForAbove(static_cast<std::int64_t>(L.n[1]) * L.n[2], kLevelSerialBelow,
                     [&](std::int64_t line) { firstHalfSweepFromZero(L, line, line + 1); });
    smoothColour(L, 1);
    for (int s = 1; s < kPreSmooth; ++s) smoothPair(L, 0);
  }
  PoissonLevel& C = levels_[l + 1];
  const std::array<int, 3> f = factors_[l];
  const int nx = L.n[0], ny = L.n[1];
  const int cx = C.n[0], cy = C.n[1], cz = C.n[2];
  // Residual fused with the restriction (sum of the children's residuals: volume-integrated
  // equations): the fine residual of each child line is computed into a per-thread line buffer
  // and added to its coarse line, in the same order (dk, dj, di) as a separate pass would.
  const std::size_t stride = static_cast<std::size_t>(nx) + 8;  // padding: no false sharing
  if (lineBuffer_.size() < stride * static_cast<std::size_t>(gf::threadCount()))
    lineBuffer_.resize(stride * static_cast<std::size_t>(gf::threadCount()));
  parallelForAbove(static_cast<std::int64_t>(cy) * cz, kLevelSerialBelow, [&](std::int64_t line) {
    const int J = static_cast<int>(line % cy), K = static_cast<int>(line / cy);
    double* r = lineBuffer_.data() + stride * static_cast<std::size_t>(omp_get_thread_num());
    double* cb = C.b.data() + static_cast<std::size_t>(cx) * line;
    std::fill(cb, cb + cx, 0.0);
    const int dkEnd = std::min(f[2], L.n[2] - K * f[2]), djEnd = std::min(f[1], ny - J * f[1]);
    for (int dk = 0; dk < dkEnd; ++dk)
      for (int dj = 0; dj < djEnd; ++dj) {
        const int j = J * f[1] + dj, k = K * f[2] + dk;
        applyLine(L, L.x.data(), r, j, k, zeros_.data());
        const double* b = L.b.data() + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k);
        if (f[0] == 2) {
          for (int I = 0; I < cx; ++I) {
            cb[I] += b[2 * I] - r[2 * I];
            if (2 * I + 1 < nx) cb[I] += b[2 * I + 1] - r[2 * I + 1];
          }
        } else {
          for (int I = 0; I < cx; ++I) cb[I] += b[I] - r[I];
        }
      }
  });
  vcycle(l + 1);
  // Prolongation: piecewise constant, added to the children.
  parallelForAbove(static_cast<std::int64_t>(L.n[1]) * L.n[2], kLevelSerialBelow, [&](std::int64_t line) {
    const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
    const std::size_t cbase = static_cast<std::size_t>(cx) * (j / f[1] + static_cast<std::size_t>(cy) * (k / f[2]));
    const std::size_t base = static_cast<std::size_t>(nx) * line;
    prolongLine(L.x.data() + base, C.x.data() + cbase, nx, f[0]);
  });
  if (!L.redBlackSafe) {
    for (int s = 0; s < kPostSmooth; ++s) symmetricGaussSeidel(L);
  } else {
    for (int s = 0; s < kPostSmooth; ++s) smoothPair(L, 1);
  }
}

void MultigridPoisson::apply(const std::vector<double>& x, std::vector<double>& y) const {
  if (callerCell_.empty()) return applyLevel(levels_[0], x, y);
  std::vector<double> xi(callerCell_.size()), yi(callerCell_.size());
  for (std::size_t c = 0; c < xi.size(); ++c) xi[c] = x[callerCell_[c]];
  applyLevel(levels_[0], xi, yi);
  for (std::size_t c = 0; c < yi.size(); ++c) y[callerCell_[c]] = yi[c];
}

bool MultigridPoisson::teamEligible() const {
  return levels_.size() >= 2 && levels_[0].redBlackSafe && static_cast<std::int64_t>(levels_[0].cells()) < kSerialCellsBelow;
}

PoissonResult MultigridPoisson::solve(std::vector<double>& x, const std::vector<double>& b, double tol,
                                      int maxIterations) {
  if (!teamEligible()) return solveMgpcg(x, b, tol, maxIterations, 1);
  // A small grid: one thread, or a team in one parallel region, whichever the tuner finds faster
  // (speed only: the same result for either).
  const PoissonLevel& F = levels_[0];
  const auto cells = static_cast<std::int64_t>(F.cells());
  const int maxTeam = static_cast<int>(std::min<std::int64_t>(
      {gf::threadCount(), F.n[2], levels_[1].n[2], std::max<std::int64_t>(1, cells / kTeamCellsPerThread)}));
  const int team = team_.pick(maxTeam);
  const double started = TeamTuner::now();
  const PoissonResult r = solveMgpcg(x, b, tol, maxIterations, team);
  // per iteration (+1: the setup of the residual): the iteration count varies from step to step
  // (5-8 in the bubbling bed), which would otherwise decide the comparison of single probes
  team_.record(team, (TeamTuner::now() - started) / (r.iterations + 1));
  return r;
}

// MGPCG (one V-cycle as the preconditioner), written once for both ways of threading it:
//   - team > 1 (small grids): one parallel region; member t owns the fine planes [k0, k1) (grid
//     lines j + ny k) and the coarse planes [K0, K1) of level 1, whose right-hand sides (fused
//     residual + restriction) it computes; levels >= 1 run on member 0, between barriers;
//   - team = 1: the calling thread, whose line loops (forLines) and V-cycle (vcycle(0)) thread
//     themselves loop by loop (large grids; serial on a small grid's serial scope).
// r and z live in the fine level's b and x (no copies). Red-black half-sweeps update only one
// colour from the other, and the fused pairs of smoothPair give the values of two half-sweeps: the
// same values for any split. Dot products and means: per-line sums (teamSums_) added in line order
// by every member (the same decisions everywhere, no extra barrier; the same bits for any team size
// or thread count).
// Singular problems (pure Neumann or periodic): the right-hand side is made compatible (its mean
// over the coupled cells removed), the preconditioned residual is projected to zero mean (except for
// constant coefficients with every cell coupled, below) and so is the solution at the end.
PoissonResult MultigridPoisson::solveMgpcg(std::vector<double>& xv, const std::vector<double>& bv, double tol,
                                           int maxIterations, int team) {
  PoissonLevel& L = levels_[0];
  const bool inTeam = team > 1;  // (solve picks a team only where teamEligible)
  const bool twoLevels = levels_.size() >= 2;
  const std::array<int, 3> f = twoLevels ? factors_[0] : std::array<int, 3>{1, 1, 1};
  PoissonLevel& C = levels_[twoLevels ? 1 : 0];
  const int nx = L.n[0], ny = L.n[1], nz = L.n[2];
  const int cx = C.n[0], cy = C.n[1], cz = C.n[2];
  const auto lines = static_cast<std::size_t>(ny) * nz;
  for (auto& v : teamSums_) v.assign(lines, 0.0);
  const std::size_t stride = static_cast<std::size_t>(nx) + 8;
  // Sized for vcycle(1) too (it must not reallocate while the members hold their lines).
  const auto buffers = static_cast<std::size_t>(std::max(team, gf::threadCount()));
  if (lineBuffer_.size() < stride * buffers) lineBuffer_.resize(stride * buffers);
  PoissonResult result;
  // x and b in the caller's cell order (callerCell_), or the internal one (callerCell_ empty).
  const bool permuted = !callerCell_.empty();
  double* x = permuted ? xInternal_.data() : xv.data();
  const double* b = permuted ? bInternal_.data() : bv.data();
  const std::size_t* caller = callerCell_.data();
  double* r = L.b.data();  // residual (the fine level's right-hand side)
  double* z = L.x.data();  // preconditioned residual (the fine level's solution)
  double* p = p_.data();
  double* q = q_.data();
  const double* inv = L.invDiag.data();  // 0: a cell without coupling (blocked), left out of means
  const double* zeros = zeros_.data();
  const bool gauge = singular_ && activeCells_ > 0.0;
  // Constant coefficients and every cell coupled (a closed box of single-phase flow): z's
  // projection would be a full pass that changes nothing CG needs. A constant added to z changes
  // neither r . z (r has zero mean) nor A p (constants are A's null space), the coarsest solve keeps
  // that constant small (zero-mean solution, factorCoarsest), and x's mean goes at the end. (Other
  // singular problems keep it: blocked cells must stay 0.)
  const bool zGauge = gauge && !(L.constantT && activeCells_ == static_cast<double>(L.cells()));
  gf::TeamBarrier barrier(team);  // (~96 per call: a spin barrier, core/parallel.hpp)
  auto member = [&]() {
    const int t = inTeam ? omp_get_thread_num() : 0;
    const int members = inTeam ? omp_get_num_threads() : 1;  // fewer than asked: still all planes
    const std::int64_t lb = static_cast<std::int64_t>(ny) * (nz * t / members);
    const std::int64_t le = static_cast<std::int64_t>(ny) * (nz * (t + 1) / members);
    const int K0 = cz * t / members, K1 = cz * (t + 1) / members;
    double* lineR = lineBuffer_.data() + stride * static_cast<std::size_t>(t);
    // The member's grid lines: its own planes in a team, else every line, threaded loop by loop.
    auto forLines = [&](auto&& body) {
      if (inTeam) {
        for (std::int64_t line = lb; line < le; ++line) body(line);
      } else {
        parallelForAbove(static_cast<std::int64_t>(lines), kLevelSerialBelow, body);
      }
    };
    auto sum = [&](int which) { return sumOfPartials(teamSums_[which]); };
    auto lineDot = [&](const double* a, const double* c, std::int64_t line) {
      const std::size_t base = static_cast<std::size_t>(nx) * line;
      return serialSum4(nx, [&](std::int64_t i) { return a[base + i] * c[base + i]; });
    };
    auto lineCoupledSum = [&](const double* a, std::int64_t line) {
      const std::size_t base = static_cast<std::size_t>(nx) * line;
      return serialSum4(nx, [&](std::int64_t i) { return inv[base + i] > 0.0 ? a[base + i] : 0.0; });
    };
    auto subtractOnLine = [&](double* a, double mean, std::int64_t line) {
      const std::size_t base = static_cast<std::size_t>(nx) * line;
      for (int i = 0; i < nx; ++i) a[base + i] = inv[base + i] > 0.0 ? a[base + i] - mean : 0.0;
    };
    auto halfSweep = [&](int colour) {
      for (std::int64_t line = lb; line < le; ++line)
        relaxLine(L, static_cast<int>(line % ny), static_cast<int>(line / ny), colour);
    };
    // z = one V-cycle applied to r, then r . z. In a team, vcycle(0)'s steps with the members'
    // planes: kPreSmooth red-black pairs before, kPostSmooth black-red pairs after.
    // The V-cycle's first step (z = 0, then the first red half-sweep) reads only the member's own
    // lines of r: it is run right after the member's r update, before the barrier that completes
    // the norms (nobody reads z between the previous V-cycle's last barrier and the next one; if
    // the norm then says converged, z is not used). One barrier less per iteration (one thread:
    // after the check, no sweep for nothing on convergence).
    const bool earlySweep = inTeam && members > 1;
    auto vcycleTeam = [&]() {
      if (!earlySweep) firstHalfSweepFromZero(L, lb, le);
      halfSweep(1);
      barrier.wait();
      for (int s = 1; s < kPreSmooth; ++s) {
        halfSweep(0);
        barrier.wait();
        halfSweep(1);
        barrier.wait();
      }
      for (int K = K0; K < K1; ++K)
        for (int J = 0; J < cy; ++J) {
          double* cb = C.b.data() + static_cast<std::size_t>(cx) * (J + static_cast<std::size_t>(cy) * K);
          std::fill(cb, cb + cx, 0.0);
          const int dkEnd = std::min(f[2], nz - K * f[2]), djEnd = std::min(f[1], ny - J * f[1]);
          for (int dk = 0; dk < dkEnd; ++dk)
            for (int dj = 0; dj < djEnd; ++dj) {
              const int j = J * f[1] + dj, k = K * f[2] + dk;
              applyLine(L, z, lineR, j, k, zeros);
              const double* bl = r + static_cast<std::size_t>(nx) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * k);
              if (f[0] == 2) {
                for (int I = 0; I < cx; ++I) {
                  cb[I] += bl[2 * I] - lineR[2 * I];
                  if (2 * I + 1 < nx) cb[I] += bl[2 * I + 1] - lineR[2 * I + 1];
                }
              } else {
                for (int I = 0; I < cx; ++I) cb[I] += bl[I] - lineR[I];
              }
            }
        }
      barrier.wait();
      if (t == 0) vcycle(1);
      barrier.wait();
      for (std::int64_t line = lb; line < le; ++line) {
        const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
        const std::size_t cbase = static_cast<std::size_t>(cx) * (j / f[1] + static_cast<std::size_t>(cy) * (k / f[2]));
        const std::size_t base = static_cast<std::size_t>(nx) * line;
        prolongLine(z + base, C.x.data() + cbase, nx, f[0]);
      }
      for (int s = 0; s < kPostSmooth; ++s) {
        barrier.wait();
        halfSweep(1);
        barrier.wait();
        halfSweep(0);
      }
    };
    auto precondition = [&]() {
      if (inTeam) vcycleTeam();
      else vcycle(0);
      if (zGauge) {  // (the last half-sweep wrote only own values of z)
        forLines([&](std::int64_t line) { teamSums_[4][static_cast<std::size_t>(line)] = lineCoupledSum(z, line); });
        barrier.wait();
        const double mean = sum(4) / activeCells_;
        forLines([&](std::int64_t line) {
          subtractOnLine(z, mean, line);
          teamSums_[3][static_cast<std::size_t>(line)] = lineDot(r, z, line);
        });
      } else {
        forLines([&](std::int64_t line) { teamSums_[3][static_cast<std::size_t>(line)] = lineDot(r, z, line); });
      }
      barrier.wait();
      return sum(3);
    };
    if (permuted) {
      double* xi = xInternal_.data();
      double* bi = bInternal_.data();
      const double* xc = xv.data();
      const double* bc = bv.data();
      forLines([&](std::int64_t line) {
        for (auto c = static_cast<std::size_t>(nx * line); c < static_cast<std::size_t>(nx * (line + 1)); ++c) {
          xi[c] = xc[caller[c]];
          bi[c] = bc[caller[c]];
        }
      });
      barrier.wait();  // (A x reads the neighbouring members' planes of x)
    }
    // r = b - A x; ||b||, ||r||. Singular: b's mean over the coupled cells removed first (a
    // compatible right-hand side), then r's (round-off: A's columns sum to 0).
    double bMean = 0.0;
    if (gauge) {
      forLines([&](std::int64_t line) { teamSums_[4][static_cast<std::size_t>(line)] = lineCoupledSum(b, line); });
      barrier.wait();
      bMean = sum(4) / activeCells_;
    }
    forLines([&](std::int64_t line) {
      const std::size_t base = static_cast<std::size_t>(nx) * line;
      applyLine(L, x, q + base, static_cast<int>(line % ny), static_cast<int>(line / ny), zeros);
      if (gauge) {
        for (int i = 0; i < nx; ++i) r[base + i] = (inv[base + i] > 0.0 ? b[base + i] - bMean : 0.0) - q[base + i];
        teamSums_[0][static_cast<std::size_t>(line)] = serialSum4(nx, [&](std::int64_t i) {
          const double bc = inv[base + i] > 0.0 ? b[base + i] - bMean : 0.0;
          return bc * bc;
        });
        teamSums_[5][static_cast<std::size_t>(line)] = lineCoupledSum(r, line);
      } else {
        for (int i = 0; i < nx; ++i) r[base + i] = b[base + i] - q[base + i];
        teamSums_[0][static_cast<std::size_t>(line)] = lineDot(b, b, line);
        teamSums_[1][static_cast<std::size_t>(line)] = lineDot(r, r, line);
      }
    });
    if (gauge) {
      barrier.wait();
      const double rMean = sum(5) / activeCells_;
      forLines([&](std::int64_t line) {
        subtractOnLine(r, rMean, line);
        teamSums_[1][static_cast<std::size_t>(line)] = lineDot(r, r, line);
      });
    }
    if (earlySweep) firstHalfSweepFromZero(L, lb, le);  // the V-cycle's first step
    barrier.wait();
    const double bnorm = std::sqrt(sum(0));
    double rnorm = std::sqrt(sum(1));
    int iterations = 0;
    double relative = bnorm > 0.0 ? rnorm / bnorm : 0.0;
    if (bnorm == 0.0) {
      forLines([&](std::int64_t line) { std::fill(x + nx * line, x + nx * (line + 1), 0.0); });
    } else if (relative > tol) {
      double rz = precondition();
      forLines([&](std::int64_t line) { std::copy(z + nx * line, z + nx * (line + 1), p + nx * line); });
      for (int it = 1; it <= maxIterations; ++it) {
        barrier.wait();  // p complete
        forLines([&](std::int64_t line) {
          applyLine(L, p, q + nx * line, static_cast<int>(line % ny), static_cast<int>(line / ny), zeros);
          teamSums_[2][static_cast<std::size_t>(line)] = lineDot(p, q, line);
        });
        barrier.wait();
        const double pq = sum(2);
        if (pq <= 0.0) break;
        const double alpha = rz / pq;
        forLines([&](std::int64_t line) {
          const std::size_t base = static_cast<std::size_t>(nx) * line;
          for (int i = 0; i < nx; ++i) {
            x[base + i] += alpha * p[base + i];
            r[base + i] -= alpha * q[base + i];
          }
          teamSums_[1][static_cast<std::size_t>(line)] = lineDot(r, r, line);
        });
        if (earlySweep) firstHalfSweepFromZero(L, lb, le);  // the V-cycle's first step
        barrier.wait();
        rnorm = std::sqrt(sum(1));
        iterations = it;
        relative = rnorm / bnorm;
        if (relative <= tol) break;
        const double rzNew = precondition();
        const double beta = rzNew / rz;
        rz = rzNew;
        forLines([&](std::int64_t line) {
          const std::size_t base = static_cast<std::size_t>(nx) * line;
          for (int i = 0; i < nx; ++i) p[base + i] = z[base + i] + beta * p[base + i];
        });
      }
    }
    if (gauge && bnorm > 0.0) {  // x's mean over the coupled cells removed (own lines of x)
      forLines([&](std::int64_t line) { teamSums_[5][static_cast<std::size_t>(line)] = lineCoupledSum(x, line); });
      barrier.wait();
      const double xMean = sum(5) / activeCells_;
      forLines([&](std::int64_t line) { subtractOnLine(x, xMean, line); });
    }
    if (permuted) {  // the member's lines of x are final
      double* xc = xv.data();
      forLines([&](std::int64_t line) {
        for (auto c = static_cast<std::size_t>(nx * line); c < static_cast<std::size_t>(nx * (line + 1)); ++c) xc[caller[c]] = x[c];
      });
    }
    if (t == 0) {
      result.iterations = iterations;
      result.relativeResidual = relative;
      result.converged = relative <= tol;
    }
  };
  runTeam(team, member);  // (a team of one: no region, core/parallel.hpp)
  return result;
}

}  // namespace gf::fluid
