#pragma once
// Variable density in the pressure projection (VOF mixtures, seed 002 eqs. 3 and 6).
//
// The projection solves  div( eps_f a_f / A_f grad phi ) = div(eps u*) + (eps - eps_old)/dt  with
// A_f = rho_f gamma0 eps_f / dt + K_f (docs/fluid.md). With a mixture density rho_f that varies in
// space, the face coefficient carries 1/rho_f; MultigridPoisson and HyprePressure take any
// non-negative face transmissibilities T_f, so only the coefficients change.
//
// Face density: the arithmetic mean rho_f = (rho_L + rho_R)/2 of the two cells. For a face
// coefficient beta = 1/rho this is the harmonic mean of beta, 2 beta_L beta_R / (beta_L + beta_R):
// the two half cells in series, each with its own coefficient, which carries the flux across a
// coefficient jump exactly (Patankar 1980, Numerical Heat Transfer and Fluid Flow, sec. 4.2-3,
// "interface conductivity"). The arithmetic mean of beta instead would let the light side's
// coefficient (1000 times the heavy side's at water/air) set the face. The same rho_f also makes
// the discrete hydrostatic balance exact: with the modified pressure p* = p - rho (g.x) of
// seed 002 eq. 6 and the face force -(g.x)_f (rho_R - rho_L)/h, the pressure p that balances the
// column has (p_R - p_L)/h = rho_f g_a with exactly this rho_f (see hydrostaticFaceForce).
//
// Pure formulas and one loop over a box of cells whose ghost layers are filled (by the solver's
// ghost fill, i.e. the exchange between ranks on a decomposed grid), so it works on a rank's box.
//
// The solvers need no change for a 1000:1 jump: MultigridPoisson's coarse T (sum of the fine T on
// the coarse face / 2 for even counts) is half the Galerkin product R A P of piecewise-constant
// prolongation P and R = P^T (the aggregation coarse operator, scaled as in Braess 1995, Computing
// 55), which follows the fine coefficients wherever the jump lies; hypre's PFMG builds its own
// Galerkin coarse operators (tests/fluid/variable_density_test.cpp has the iteration counts).
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/grid.hpp"

namespace gf::fluid {

/// Mixture density on a face between cells of densities rhoL and rhoR: the arithmetic mean, i.e.
/// the harmonic mean of the coefficient 1/rho (Patankar 1980, sec. 4.2-3; see above).
inline double faceDensity(double rhoL, double rhoR) { return 0.5 * (rhoL + rhoR); }

/// Projection face coefficient a_f / (rho_f gamma0 eps_f / dt + K_f) of the velocity correction
/// u = u* - coefficient * grad phi (docs/fluid.md, Projection); a_f = eps_f (model A) or 1 (B).
/// For constant rho it is the solver's correctionCoeff with the same operations.
inline double projectionCoefficient(double epsF, double rhoF, double gamma0OverDt, double KF, bool modelA) {
  return (modelA ? epsF : 1.0) / (rhoF * gamma0OverDt * epsF + KF);
}

/// Face value of seed 002 eq. 6's buoyancy term -(g.x) grad rho_f, per unit volume, on the face
/// between cells L and R along an axis of spacing h; gDotXFace = g . x at the face centre.
inline double hydrostaticFaceForce(double gDotXFace, double rhoL, double rhoR, double h) {
  return -gDotXFace * (rhoR - rhoL) / h;
}

/// Pressure from the modified pressure, p = p* + rho (g.x) (seed 002, line 330).
inline double pressureFromModified(double pStar, double rho, double gDotX) { return pStar + rho * gDotX; }

/// Which faces of the box along an axis side carry a coupling: Wall = none (Neumann: T = 0),
/// Coupled = from the cell and its ghost (periodic wrap, a neighbour rank across a cut, or a
/// Dirichlet face, whose ghost the caller fills with the cell's own value, so the face takes the
/// cell's coefficient).
enum class FaceCoupling : std::uint8_t { Wall, Coupled };

/// Face transmissibilities T_f = eps_f beta_f area_f / h_f, beta_f = projectionCoefficient, for
/// MultigridPoisson::setup / HyprePressure::setup (array of axis a: (n_a + 1) faces along a, x
/// fastest). eps, rho, K: cell fields of the box with their ghost layers filled; eps_f and K_f
/// the arithmetic means of the two cells (as the solver's projection), rho_f = faceDensity.
/// Axes with one cell (2D) get T = 0. sides[2a + s]: coupling of the lower (s = 0) / upper face.
inline std::array<std::vector<double>, 3> variableDensityTransmissibilities(
    const Field& eps, const Field& rho, const Field& K, double gamma0OverDt, bool modelA,
    const std::array<FaceCoupling, 6>& sides) {
  const CartesianGrid& grid = eps.grid();
  const std::array<int, 3>& n = grid.cells;
  std::array<std::vector<double>, 3> T;
  const double* E = eps.data().data();
  const double* R = rho.data().data();
  const double* Kc = K.data().data();
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> fn = n;
    fn[a] += 1;
    T[a].assign(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2], 0.0);
    if (n[a] == 1) continue;
    const double h = a == 0 ? grid.spacing.x : (a == 1 ? grid.spacing.y : grid.spacing.z);
    const double areaOverH = grid.cellVolume() / (h * h);
    const std::ptrdiff_t s = eps.stride(a);
    std::size_t out = 0;
    for (int k = 0; k < fn[2]; ++k)
      for (int j = 0; j < fn[1]; ++j)
        for (int i = 0; i < fn[0]; ++i, ++out) {
          const int along = a == 0 ? i : (a == 1 ? j : k);
          if ((along == 0 && sides[2 * a] == FaceCoupling::Wall) ||
              (along == n[a] && sides[2 * a + 1] == FaceCoupling::Wall))
            continue;
          const std::size_t cR = eps.index(i, j, k);  // the cell above the face (a ghost at along = n)
          const std::size_t cL = cR - s;
          const double epsF = 0.5 * (E[cL] + E[cR]);
          const double beta = projectionCoefficient(epsF, faceDensity(R[cL], R[cR]), gamma0OverDt,
                                                    0.5 * (Kc[cL] + Kc[cR]), modelA);
          T[a][out] = epsF * beta * areaOverH;
        }
  }
  return T;
}

}  // namespace gf::fluid
