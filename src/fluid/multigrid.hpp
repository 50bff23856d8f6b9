#pragma once
// Variable-coefficient Poisson solver: conjugate gradients preconditioned by one geometric
// multigrid V-cycle (MGPCG; Tatebe 1993, McAdams et al. 2010).
//
// The operator is written in finite-volume, volume-integrated form on cell centres:
//   (A x)_c = sum_faces T_f (x_c - x_nb)          (+ 2 T_f x_c on Dirichlet boundary faces)
// with face transmissibilities T_f = beta_f * area_f / spacing_f >= 0 (beta = eps-weighted
// 1/(rho gamma0/dt + K)); A is symmetric positive (semi-)definite.
//
// Multigrid: cell-centred coarsening by 2 in every direction with more than 1 cell (odd counts
// leave a last coarse cell of one fine cell), coarse
// transmissibility = sum of the covered fine ones / distance of the coarse centres in fine cells
// (rediscretisation), restriction = sum of children, prolongation = piecewise constant
// (its transpose), red-black Gauss-Seidel smoothing (red-black before, black-red after, so the
// V-cycle is a symmetric operator and CG stays valid), a dense Cholesky solve on the coarsest
// level (<= 64 cells; symmetric Gauss-Seidel sweeps if that is not possible). Pure Neumann/periodic problems are singular: the mean is projected out.
#include <array>
#include <cstdint>
#include <vector>

#include "fluid/team_tuner.hpp"

namespace gf::fluid {

struct PoissonLevel {
  std::array<int, 3> n{1, 1, 1};
  std::array<bool, 3> periodic{false, false, false};
  std::array<std::vector<double>, 3> T;  // face transmissibilities, (n_a + 1) along axis a
  std::vector<double> invDiag;           // 1 / diagonal, 0 for cells without any coupling
  std::vector<double> diag;              // diagonal
  std::vector<double> x, b;              // solution, right-hand side
  bool redBlackSafe = true;              // colouring is a proper 2-colouring (no odd periodic axis)
  /// Every face that couples two cells along axis a has T = tConstant[a] (uniform coefficients,
  /// e.g. single-phase flow): the smoother and the operator then read no coefficient arrays.
  bool constantT = false;
  std::array<double, 3> tConstant{0.0, 0.0, 0.0};

  std::size_t cells() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  /// Index of face (i, j, k) normal to axis (axis -1: cell (i, j, k)).
  std::size_t faceIndex(int axis, int i, int j, int k) const {
    const std::size_t nx = n[0] + (axis == 0), ny = n[1] + (axis == 1);
    return static_cast<std::size_t>(i) + nx * (static_cast<std::size_t>(j) + ny * static_cast<std::size_t>(k));
  }
};

struct PoissonResult {
  int iterations = 0;
  double relativeResidual = 0.0;
  bool converged = true;
};

class MultigridPoisson {
 public:
  /// Fine-level setup. T[a] holds (n_a+1) faces along a; boundary faces carry the Dirichlet
  /// transmissibility where dirichlet[2a+side] is set (0 elsewhere, i.e. Neumann), periodic
  /// boundary faces carry the wrap-around coupling (face n_a equals face 0).
  void setup(const std::array<int, 3>& n, const std::array<bool, 3>& periodic,
             const std::array<std::vector<double>, 3>& T, const std::array<bool, 6>& dirichlet);

  /// Solves A x = b (x holds the initial guess) to ||b - A x|| <= tol ||b||.
  PoissonResult solve(std::vector<double>& x, const std::vector<double>& b, double relativeTolerance,
                      int maxIterations);

  bool singular() const { return singular_; }
  int levels() const { return static_cast<int>(levels_.size()); }
  /// y = A x on the fine level (caller's cell order).
  void apply(const std::vector<double>& x, std::vector<double>& y) const;

 private:
  /// Small grids (below kSerialCellsBelow cells, two levels or more, red-black colourable): solve
  /// may run the solver as a team in one parallel region (solveMgpcg).
  bool teamEligible() const;
  /// MGPCG in one implementation for a team of `team` threads in one parallel region (the members
  /// split the planes of the fine level, coarser levels run on member 0) or, team = 1, for the
  /// calling thread with loops that thread themselves: the same result for any team size and
  /// thread count (sums per grid line, in line order). x and b are in the caller's cell order.
  PoissonResult solveMgpcg(std::vector<double>& x, const std::vector<double>& b, double relativeTolerance,
                           int maxIterations, int team);
  void buildDiagonal(PoissonLevel& L, const std::array<bool, 6>& dirichlet) const;
  // buildDiagonal in parts: constantT / redBlackSafe (whole level), sizes, grid lines (threads
  // may split the lines).
  static void classifyLevel(PoissonLevel& L);
  static void allocateDiagonal(PoissonLevel& L);
  static void diagonalLines(PoissonLevel& L, const std::array<bool, 6>& dirichlet, std::int64_t lineBegin,
                            std::int64_t lineEnd);
  void coarsen(const PoissonLevel& fine, PoissonLevel& coarse, const std::array<int, 3>& factor) const;
  // coarsen in parts: the coarse shape and array sizes, then the coarse faces of axis a on the
  // face array's grid lines [lineBegin, lineEnd).
  static void coarsenShape(const PoissonLevel& fine, PoissonLevel& coarse, const std::array<int, 3>& factor);
  static void coarsenLines(const PoissonLevel& fine, PoissonLevel& coarse, const std::array<int, 3>& factor, int a,
                           std::int64_t lineBegin, std::int64_t lineEnd);
  void applyLevel(const PoissonLevel& L, const std::vector<double>& x, std::vector<double>& y) const;
  void relaxLine(PoissonLevel& L, int j, int k, int colour) const;
  void smoothColour(PoissonLevel& L, int colour) const;
  void smoothPair(PoissonLevel& L, int first) const;
  void symmetricGaussSeidel(PoissonLevel& L) const;
  void factorCoarsest();
  void solveCoarsest(PoissonLevel& L) const;
  void vcycle(int level);

  std::vector<PoissonLevel> levels_;
  std::vector<std::array<int, 3>> factors_;  // coarsening factor from level l to l+1
  std::array<bool, 6> dirichlet_{};
  bool singular_ = true;
  double activeCells_ = 0.0;  // fine cells with a non-zero diagonal
  std::vector<double> p_, q_;       // CG direction and A p (r and z live in the fine level's b and x)
  std::vector<double> lineBuffer_;  // per-thread residual line of the fused restriction
  // Internally the longest axis is the fastest-varying one (a 2 x 30 x 90 bed is stored as
  // 90 x 2 x 30: long grid lines, little per-line overhead); perm_[internal axis] = caller's axis,
  // callerCell_[internal cell] = the caller's index of that cell (empty when perm_ is the identity).
  std::array<int, 3> perm_{0, 1, 2};
  std::vector<std::size_t> callerCell_;
  std::vector<double> xInternal_, bInternal_;
  std::vector<double> zeros_;           // zero coefficient line (missing neighbours), n_x + 1 long
  std::vector<double> teamSums_[6];     // per-line partial sums of solveMgpcg (b.b, r.r, p.Ap, r.z, two for means)
  TeamTuner team_;                      // one thread or a team for solveMgpcg (speed only)
  TeamTuner setupTeam_;                 // one thread or a team for setup's fine levels (speed only)
  std::array<int, 3> callerN_{0, 0, 0};  // grid of callerCell_
  std::vector<double> coarseCholesky_;  // dense Cholesky factor of the coarsest level (empty: GS sweeps)
};

}  // namespace gf::fluid
