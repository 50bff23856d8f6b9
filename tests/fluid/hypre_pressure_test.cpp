// The hypre pressure solver (fluid/hypre_pressure.hpp) against grainflow's multigrid on the same
// linear systems, and on manufactured solutions:
//  - variable coefficients with Neumann, periodic and Dirichlet sides and blocked cells: the two
//    solutions agree to the solver tolerance (both stop at ||b - A x|| <= tol ||b||, so they differ
//    by at most about cond(A) tol; 1e-10 tolerances, compared at 1e-7 of the solution's size);
//  - -lap u = f with u known: second-order convergence (the error falls by ~4 from n = 16 to 32;
//    accepted above 3.5) with Dirichlet and periodic sides, and a fully periodic (singular) box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fluid/hypre_pressure.hpp"
#include "fluid/multigrid.hpp"
#include "parallel/environment.hpp"

namespace gf::fluid {
namespace {

struct System {
  std::array<int, 3> n;
  std::array<bool, 3> periodic;
  std::array<bool, 6> dirichlet;
  std::array<std::vector<double>, 3> T;
  std::vector<double> b;
};

std::size_t cellCount(const std::array<int, 3>& n) { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }

/// Faces with an eps-like coefficient varying by a factor 4; faces of blocked cells (a box of
/// cells inside the grid when `block`) carry no coupling.
System variableSystem(const std::array<int, 3>& n, const std::array<bool, 3>& periodic, const std::array<bool, 6>& dirichlet,
                      bool block) {
  System s{n, periodic, dirichlet, {}, {}};
  auto blocked = [&](int i, int j, int k) {
    return block && i >= n[0] / 4 && i < n[0] / 2 && j >= n[1] / 4 && j < n[1] / 2 && k >= n[2] / 4 && k <= n[2] / 2;
  };
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = n;
    fn[a] += 1;
    s.T[a].assign(cellCount(fn), 0.0);
    if (n[a] == 1) continue;
    for (int k = 0; k < fn[2]; ++k)
      for (int j = 0; j < fn[1]; ++j)
        for (int i = 0; i < fn[0]; ++i) {
          const int idx[3] = {i, j, k};
          const bool boundary = idx[a] == 0 || idx[a] == n[a];
          if (boundary && !periodic[a] && !dirichlet[2 * a + (idx[a] == 0 ? 0 : 1)]) continue;
          int lo[3] = {i, j, k};
          lo[a] = idx[a] == 0 ? (periodic[a] ? n[a] - 1 : 0) : idx[a] - 1;
          const int hi = idx[a] == n[a] ? (periodic[a] ? 0 : n[a] - 1) : idx[a];
          int up[3] = {i, j, k};
          up[a] = hi;
          if (blocked(lo[0], lo[1], lo[2]) || blocked(up[0], up[1], up[2])) continue;
          const double x = (i + 0.5) / fn[0], y = (j + 0.5) / fn[1], z = (k + 0.5) / fn[2];
          // periodic axes: the last face equals the first (a function of the wrapped position)
          const double xp = periodic[0] && i == n[0] ? 0.5 / fn[0] : x, yp = periodic[1] && j == n[1] ? 0.5 / fn[1] : y;
          const double zp = periodic[2] && k == n[2] ? 0.5 / fn[2] : z;
          s.T[a][i + static_cast<std::size_t>(fn[0]) * (j + static_cast<std::size_t>(fn[1]) * k)] =
              0.25 + 0.75 * std::pow(std::sin(3.0 * xp + 2.0 * yp + zp), 2);
        }
  }
  const std::size_t N = cellCount(n);
  s.b.resize(N);
  for (std::size_t c = 0; c < N; ++c) {
    const int i = static_cast<int>(c % n[0]), j = static_cast<int>(c / n[0] % n[1]), k = static_cast<int>(c / n[0] / n[1]);
    s.b[c] = blocked(i, j, k) ? 0.0 : std::sin(0.37 * c) + 0.2 * std::cos(1.3 * c);
  }
  return s;
}

double maxAbs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

/// Solves s with both solvers at tol; returns max |x_hypre - x_multigrid| / max |x_multigrid|.
double compareSolvers(const System& s, double tol) {
  MultigridPoisson mg;
  mg.setup(s.n, s.periodic, s.T, s.dirichlet);
  std::vector<double> xm(s.b.size(), 0.0), xh(s.b.size(), 0.0);
  const PoissonResult rm = mg.solve(xm, s.b, tol, 500);
  HyprePressure hypre;
  hypre.setup(PressureBox::whole(s.n), s.periodic, s.T, s.dirichlet);
  const PoissonResult rh = hypre.solve(xh, s.b, tol, 500);
  EXPECT_TRUE(rm.converged);
  EXPECT_TRUE(rh.converged) << "hypre: " << rh.iterations << " iterations, residual " << rh.relativeResidual;
  EXPECT_EQ(hypre.singular(), mg.singular());
  // hypre's answer satisfies the multigrid's operator to the tolerance (the same system).
  std::vector<double> Ax(s.b.size());
  mg.apply(xh, Ax);
  double mean = 0.0, active = 0.0;
  if (mg.singular()) {
    for (std::size_t c = 0; c < s.b.size(); ++c)
      if (Ax[c] != 0.0 || s.b[c] != 0.0) mean += s.b[c], active += 1.0;
    mean /= active;
  }
  double rr = 0.0, bb = 0.0;
  for (std::size_t c = 0; c < s.b.size(); ++c) {
    const double bc = s.b[c] == 0.0 && Ax[c] == 0.0 ? 0.0 : s.b[c] - mean;
    rr += (bc - Ax[c]) * (bc - Ax[c]);
    bb += bc * bc;
  }
  EXPECT_LT(std::sqrt(rr / bb), 10.0 * tol);
  double d = 0.0;
  for (std::size_t c = 0; c < xm.size(); ++c) d = std::max(d, std::abs(xh[c] - xm[c]));
  std::printf("n=%dx%dx%d multigrid %d its, hypre %d its (residual %.2e), max difference %.2e of max |x|\n", s.n[0],
              s.n[1], s.n[2], rm.iterations, rh.iterations, rh.relativeResidual, d / maxAbs(xm));
  return d / maxAbs(xm);
}

TEST(HyprePressure, MatchesMultigridNeumann3D) {
  EXPECT_LT(compareSolvers(variableSystem({16, 12, 10}, {false, false, false}, {}, false), 1e-10), 1e-7);
}

TEST(HyprePressure, MatchesMultigridPeriodicAndDirichlet) {
  // periodic x and z (10 and 6 cells: not powers of two), a Dirichlet top, blocked cells
  EXPECT_LT(compareSolvers(variableSystem({10, 16, 6}, {true, false, true}, {false, false, false, true, false, false}, true),
                           1e-10),
            1e-7);
  // 2D (one cell in z), periodic x, Dirichlet on both y sides
  EXPECT_LT(compareSolvers(variableSystem({24, 20, 1}, {true, false, false}, {false, false, true, true, false, false}, false),
                           1e-10),
            1e-7);
}

TEST(HyprePressure, MatchesMultigridFullyPeriodicWithBlockedCells) {
  EXPECT_LT(compareSolvers(variableSystem({12, 8, 8}, {true, true, true}, {}, true), 1e-10), 1e-7);
}

TEST(HyprePressure, RepeatedSetupTakesNewCoefficients) {
  // The coupled solver sets up every step with new coefficients on the same layout.
  System s = variableSystem({12, 10, 8}, {false, false, false}, {false, false, false, false, false, true}, false);
  HyprePressure hypre;
  hypre.setup(PressureBox::whole(s.n), s.periodic, s.T, s.dirichlet);
  std::vector<double> x(s.b.size(), 0.0);
  hypre.solve(x, s.b, 1e-10, 200);
  for (auto& T : s.T)
    for (double& t : T) t *= 3.0;
  hypre.setup(PressureBox::whole(s.n), s.periodic, s.T, s.dirichlet);
  std::vector<double> x3(s.b.size(), 0.0);
  const PoissonResult r = hypre.solve(x3, s.b, 1e-10, 200);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(hypre.setups(), 2);
  for (std::size_t c = 0; c < x.size(); ++c) EXPECT_NEAR(3.0 * x3[c], x[c], 1e-8 * maxAbs(x));
}

TEST(HyprePressure, SplitBoxesMatchMultigrid) {
  // Each rank passes its slab of z planes (one rank: the whole grid) with the faces of that slab;
  // hypre couples the slabs. ctest runs this under mpirun -n 2 as well.
  const System s = variableSystem({12, 10, 16}, {true, false, false}, {false, false, false, false, false, true}, true);
  MultigridPoisson mg;
  mg.setup(s.n, s.periodic, s.T, s.dirichlet);
  std::vector<double> xm(s.b.size(), 0.0);
  ASSERT_TRUE(mg.solve(xm, s.b, 1e-11, 500).converged);
  const parallel::Environment& env = parallel::Environment::instance();
  const int k0 = env.rank() * s.n[2] / env.size(), k1 = (env.rank() + 1) * s.n[2] / env.size();
  const PressureBox box{s.n, {0, 0, k0}, {s.n[0], s.n[1], k1 - k0}};
  // The slab's faces: planes k0 .. k1 - 1 of x and y faces, k0 .. k1 of z faces.
  std::array<std::vector<double>, 3> T;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = s.n;
    fn[a] += 1;
    const std::size_t plane = static_cast<std::size_t>(fn[0]) * fn[1];
    T[a].assign(s.T[a].begin() + plane * k0, s.T[a].begin() + plane * (k1 + (a == 2)));
  }
  const std::size_t plane = static_cast<std::size_t>(s.n[0]) * s.n[1];
  const std::vector<double> b(s.b.begin() + plane * k0, s.b.begin() + plane * k1);
  std::vector<double> x(b.size(), 0.0);
  HyprePressure hypre;
  hypre.setup(box, s.periodic, T, s.dirichlet);
  const PoissonResult r = hypre.solve(x, b, 1e-11, 500);
  EXPECT_TRUE(r.converged);
  double d = 0.0;
  for (std::size_t c = 0; c < x.size(); ++c) d = std::max(d, std::abs(x[c] - xm[plane * k0 + c]));
  std::printf("rank %d of %d, planes %d-%d: %d iterations, max difference %.2e of max |x|\n", env.rank(), env.size(), k0,
              k1 - 1, r.iterations, d / maxAbs(xm));
  EXPECT_LT(d / maxAbs(xm), 1e-8);
}

/// -lap u = f on the unit cube with u known, in the finite-volume form of the pressure system
/// (T = area / spacing = h, b = V f): max error of the hypre solution.
double manufacturedError(int n, const std::array<bool, 3>& periodic, const std::array<bool, 6>& dirichlet) {
  const double pi = std::numbers::pi, h = 1.0 / n;
  // u = product over the axes of cos(2 pi x) (periodic axis) or sin(pi x) (Dirichlet u = 0 at
  // both ends); -lap u = (sum of the squared wave numbers) u.
  double k2 = 0.0;
  for (int a = 0; a < 3; ++a) k2 += periodic[a] ? 4.0 * pi * pi : pi * pi;
  auto exact = [&](int i, int j, int k) {
    const int idx[3] = {i, j, k};
    double u = 1.0;
    for (int a = 0; a < 3; ++a) {
      const double x = (idx[a] + 0.5) * h;
      u *= periodic[a] ? std::cos(2.0 * pi * x) : std::sin(pi * x);
    }
    return u;
  };
  const std::array<int, 3> cells{n, n, n};
  std::array<std::vector<double>, 3> T;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = cells;
    fn[a] += 1;
    T[a].assign(cellCount(fn), h);  // every face couples: periodic wrap or Dirichlet boundary
  }
  const std::size_t N = cellCount(cells);
  std::vector<double> b(N), x(N, 0.0), u(N);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = i + static_cast<std::size_t>(n) * (j + static_cast<std::size_t>(n) * k);
        u[c] = exact(i, j, k);
        b[c] = h * h * h * k2 * u[c];
      }
  HyprePressure hypre;
  hypre.setup(PressureBox::whole(cells), periodic, T, dirichlet);
  const PoissonResult r = hypre.solve(x, b, 1e-12, 500);
  EXPECT_TRUE(r.converged);
  double e = 0.0;
  for (std::size_t c = 0; c < N; ++c) e = std::max(e, std::abs(x[c] - u[c]));
  return e;
}

TEST(HyprePressure, ManufacturedSolutionConvergesAtSecondOrder) {
  struct Sides {
    std::array<bool, 3> periodic;
    std::array<bool, 6> dirichlet;
  };
  const Sides sides[] = {
      {{false, false, false}, {true, true, true, true, true, true}},  // Dirichlet
      {{true, false, true}, {false, false, true, true, false, false}},  // periodic x, z; Dirichlet y
      {{true, true, true}, {}},                                         // periodic (singular, zero mean)
  };
  for (const Sides& s : sides) {
    const double e16 = manufacturedError(16, s.periodic, s.dirichlet), e32 = manufacturedError(32, s.periodic, s.dirichlet);
    std::printf("max error n=16: %.3e, n=32: %.3e, ratio %.2f\n", e16, e32, e16 / e32);
    EXPECT_LT(e32, 0.01);
    EXPECT_GT(e16 / e32, 3.5);
  }
}

}  // namespace
}  // namespace gf::fluid
