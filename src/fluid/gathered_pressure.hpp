#pragma once
// The pressure Poisson equation of a grid split among several MPI ranks, solved by grainflow's own
// multigrid (fluid/multigrid.hpp) on rank 0 for the whole grid: every rank sends its box of the
// system (face transmissibilities when they change, right-hand side and initial guess at every
// solve) to rank 0, which solves and sends each rank its box of the solution back.
//
// Why: the grids of coupled beds are small (the bubbling bed has 5,400 cells) and their cost lies
// in the particles, which the ranks share. On such a grid a distributed solver pays a message round
// per smoothing sweep and per dot product on every level; gathering costs two messages per solve.
// Gathering a small coarse problem onto fewer ranks is the usual remedy (PETSc's PCTELESCOPE, the
// agglomeration of AMReX's MLMG). The multigrid then sees the very system one rank would assemble,
// so the pressure has the bits of a one-rank run. Large grids go through hypre instead
// (fluid.pressure.gather_cells sets the size limit; fluid/hypre_pressure.hpp).
#include <array>
#include <vector>

#include "fluid/hypre_pressure.hpp"  // PressureBox
#include "fluid/multigrid.hpp"

namespace gf::fluid {

class GatheredPressure {
 public:
  /// Collective. T[a]: this box's faces normal to a, (n_a + 1) along a, as HyprePressure::setup
  /// takes them; rank 0 assembles the whole grid's faces and sets up its multigrid.
  void setup(const PressureBox& box, const std::array<bool, 3>& periodic, const std::array<std::vector<double>, 3>& T,
             const std::array<bool, 6>& dirichlet);
  /// Collective. Solves A x = b on the whole grid to ||b - A x|| <= tol ||b||; x (the box's
  /// cells, x fastest) holds the initial guess and receives the solution. Every rank gets the
  /// same result record.
  PoissonResult solve(std::vector<double>& x, const std::vector<double>& b, double relativeTolerance,
                      int maxIterations);

 private:
  PressureBox box_;
  std::vector<PressureBox> boxes_;  // rank 0: every rank's box
  MultigridPoisson poisson_;        // rank 0: the whole grid
  std::vector<double> x_, b_;       // rank 0: the whole grid's vectors
};

}  // namespace gf::fluid
