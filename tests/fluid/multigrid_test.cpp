// Multigrid-preconditioned CG: solves a variable-coefficient Poisson problem to tolerance with an
// iteration count that does not grow with the grid (the point of multigrid).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fluid/multigrid.hpp"

namespace gf::fluid {
namespace {

struct Problem {
  std::array<int, 3> n;
  std::array<bool, 3> periodic;
  std::array<bool, 6> dirichlet;
  bool variable;
};

PoissonResult solveProblem(const Problem& pb, double tol, double* residualCheck) {
  std::array<std::vector<double>, 3> T;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = pb.n;
    fn[a] += 1;
    T[a].assign(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2], 0.0);
    if (pb.n[a] == 1) continue;
    for (int k = 0; k < fn[2]; ++k)
      for (int j = 0; j < fn[1]; ++j)
        for (int i = 0; i < fn[0]; ++i) {
          const int idx[3] = {i, j, k};
          const bool boundary = idx[a] == 0 || idx[a] == pb.n[a];
          if (boundary && !pb.periodic[a] && !pb.dirichlet[2 * a + (idx[a] == 0 ? 0 : 1)]) continue;
          // eps-like coefficient varying smoothly by a factor 4 (as a packed bed would).
          const double x = (i + 0.5) / fn[0], y = (j + 0.5) / fn[1];
          const double beta = pb.variable ? 0.25 + 0.75 * std::pow(std::sin(3.0 * x + 2.0 * y), 2) : 1.0;
          T[a][i + static_cast<std::size_t>(fn[0]) * (j + static_cast<std::size_t>(fn[1]) * k)] = beta;
        }
  }
  MultigridPoisson mg;
  mg.setup(pb.n, pb.periodic, T, pb.dirichlet);
  const std::size_t N = static_cast<std::size_t>(pb.n[0]) * pb.n[1] * pb.n[2];
  std::vector<double> b(N), x(N, 0.0), Ax(N);
  for (std::size_t c = 0; c < N; ++c) b[c] = std::sin(0.37 * c) + 0.2 * std::cos(1.3 * c);
  const PoissonResult r = mg.solve(x, b, tol, 200);
  mg.apply(x, Ax);
  double mean = 0.0;
  if (mg.singular()) {
    for (double v : b) mean += v;
    mean /= N;
  }
  double rr = 0.0, bb = 0.0;
  for (std::size_t c = 0; c < N; ++c) {
    rr += std::pow(b[c] - mean - Ax[c], 2);
    bb += std::pow(b[c] - mean, 2);
  }
  *residualCheck = std::sqrt(rr / bb);
  return r;
}

TEST(Multigrid, IterationsIndependentOfGridNeumann3D) {
  int its[3];
  for (int l = 0; l < 3; ++l) {
    const int n = 8 << l;  // 8, 16, 32
    double check = 0.0;
    const auto r = solveProblem({{n, n, n}, {false, false, false}, {}, true}, 1e-8, &check);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(check, 2e-8);
    its[l] = r.iterations;
    std::printf("n=%d its=%d res=%g check=%g\n", n, r.iterations, r.relativeResidual, check);
  }
  EXPECT_LE(its[2], its[1] + 3);
  EXPECT_LE(its[2], 25);
}

TEST(Multigrid, DirichletAndPeriodic2D) {
  int its[2];
  for (int l = 0; l < 2; ++l) {
    const int n = 32 << l;
    double check = 0.0;
    const auto r = solveProblem({{n, n, 1}, {true, false, false}, {false, false, false, true, false, false}, true},
                                1e-10, &check);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(check, 2e-10);
    its[l] = r.iterations;
    std::printf("n=%d its=%d res=%g check=%g\n", n, r.iterations, r.relativeResidual, check);
  }
  EXPECT_LE(its[1], its[0] + 3);
}

TEST(Multigrid, FullyPeriodicOddCoarsening) {
  double check = 0.0;
  const auto r = solveProblem({{24, 12, 6}, {true, true, true}, {}, false}, 1e-9, &check);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(check, 2e-9);
}

// The pseudo-2D fluidised-bed grid (2 x 30 x 90, pressure outlet on top): the odd counts 15 and
// 45 must coarsen further (a rule that stops at odd counts leaves a 1350-cell coarsest level) and
// the 2-cell axis must be coarsened to 1 too (kept at 2, its coupling grows 4x per level relative
// to the others and point smoothing stalls: 15 iterations instead of 7), so the iteration count
// stays that of a cube (5-7). The long z axis is stored innermost: the residual check also tests
// the reordering.
TEST(Multigrid, ThinOddBedGridCoarsensLikeACube) {
  for (int l = 0; l < 2; ++l) {
    const int ny = 15 << l, nz = 45 << l;  // 2 x 15 x 45 and 2 x 30 x 90
    double check = 0.0;
    const auto r = solveProblem({{2, ny, nz}, {false, false, false}, {false, false, false, false, false, true}, true},
                                1e-8, &check);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(check, 2e-8);
    EXPECT_LE(r.iterations, 10);
    std::printf("2 x %d x %d: its=%d check=%g\n", ny, nz, r.iterations, check);
  }
  double check = 0.0;  // odd axes everywhere, pure Neumann (dense coarsest solve of a singular level)
  const auto r = solveProblem({{3, 45, 7}, {false, false, false}, {}, true}, 1e-8, &check);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(check, 2e-8);
  EXPECT_LE(r.iterations, 10);
}

}  // namespace
}  // namespace gf::fluid
