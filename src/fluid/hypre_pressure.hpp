#pragma once
// The pressure Poisson equation through hypre's structured (Struct) interface: conjugate gradients
// preconditioned by one PFMG V-cycle (HYPRE_StructPCG + HYPRE_StructPFMG; hypre's ex3.c), on the
// system that MultigridPoisson solves (fluid/multigrid.hpp):
//   (A x)_c = sum_faces T_f (x_c - x_nb)   (+ 2 T_f x_c on Dirichlet boundary faces),
// with the same face transmissibilities, periodic axes (a periodic hypre grid), zero-diagonal
// cells (blocked: x = 0) and, for a pure Neumann/periodic problem, the same gauge (the mean over the
// coupled cells is removed from b and from x) and the same stopping test ||b - A x|| <= tol ||b||.
//
// Each rank passes its box of the global grid (cells [lower, lower + n)) and the faces of that
// box; on one rank the box is the whole grid. hypre exchanges the values across box boundaries
// itself, so the caller only fills its own faces. Setup (grid, matrix, PFMG hierarchy) runs when
// the layout or the coefficients change; solve() every projection.
#include <array>
#include <memory>
#include <vector>

#include "fluid/multigrid.hpp"

namespace gf::fluid {

/// This rank's part of the global cell grid: cells lower[a] .. lower[a] + n[a] - 1 of global[a].
struct PressureBox {
  std::array<int, 3> global{1, 1, 1};
  std::array<int, 3> lower{0, 0, 0};
  std::array<int, 3> n{1, 1, 1};
  /// The whole grid as one box (one rank).
  static PressureBox whole(const std::array<int, 3>& cells) { return {cells, {0, 0, 0}, cells}; }
  bool operator==(const PressureBox&) const = default;
};

class HyprePressure {
 public:
  /// own = true: this process alone holds the whole grid (MPI_COMM_SELF: a solver that owns its
  /// grid in a run of several ranks); false: the ranks of the run share it (MPI_COMM_WORLD).
  explicit HyprePressure(bool own = false);
  ~HyprePressure();
  HyprePressure(const HyprePressure&) = delete;
  HyprePressure& operator=(const HyprePressure&) = delete;

  /// T[a]: the box's faces normal to a, (n_a + 1) along a in MultigridPoisson::setup's layout
  /// (x fastest). Faces on the global boundary carry the Dirichlet transmissibility where
  /// dirichlet[2a + side] is set (0 elsewhere, i.e. Neumann); on a periodic axis the last global
  /// face equals the first; faces shared with a neighbouring box carry their coupling. The first
  /// call initialises MPI (parallel::Environment) if needed.
  void setup(const PressureBox& box, const std::array<bool, 3>& periodic, const std::array<std::vector<double>, 3>& T,
             const std::array<bool, 6>& dirichlet);

  /// Solves A x = b on the box's cells (x holds the initial guess) to ||b - A x|| <= tol ||b||
  /// (global norms).
  PoissonResult solve(std::vector<double>& x, const std::vector<double>& b, double relativeTolerance,
                      int maxIterations);

  bool singular() const { return singular_; }
  /// PFMG setups so far (one per setup() call: the coefficients changed).
  int setups() const { return setups_; }

 private:
  struct Impl;  // hypre's handles (HYPRE_struct_ls.h stays out of this header)
  std::unique_ptr<Impl> impl_;
  bool own_ = false;
  PressureBox box_;
  std::array<bool, 3> periodic_{false, false, false};
  bool singular_ = true;
  int setups_ = 0;
  std::vector<double> diag_;     // per box cell; 0: a cell without coupling (x = 0)
  double activeCells_ = 0.0;     // global count of cells with a non-zero diagonal
  std::vector<double> values_;   // scratch: matrix entries, vector values
};

}  // namespace gf::fluid
