#pragma once
// Volume of fluid for N immiscible fluids inside a particle bed (docs/vof.md): the phase fractions
// alpha_i (i = 0..N-1, N >= 2) are cell fields on the fluid's MAC grid, moved by the fluid's face
// fluxes with the void fraction eps and Rusche's interface compression (seed 002, eq. 2, line 316),
// by a flux-corrected transport (upwind + Zalesak-limited Lax-Wendroff/compression correction, the
// MULES idea), and the mixture density and viscosity are their volume-weighted averages
// (seed 002, eqs. 3-4, lines 320-322).
//
// Decomposed from the start: every kernel works on one box of cells (a rank's box, or the whole
// grid) whose two ghost layers the caller fills, and global sums go through core/reduction.hpp
// (allreduces inside a parallel::RankReductionScope). A step is two stages with one ghost fill in
// between (the limiter factors of the neighbour cells); advance() runs both on one box.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/grid.hpp"
#include "core/reduction.hpp"

namespace gf::parallel {
class Decomposition;
}  // namespace gf::parallel

namespace gf::vof {

/// What lies beyond one side of a box: a periodic wrap of this box onto itself, a wall (no flux,
/// zero normal gradient of alpha), a neighbour box whose ghosts the caller exchanges, or an open
/// side (an inlet or outlet: the fluid's flux crosses it, upwind, with no correction; what flows
/// out carries the boundary cell's fractions, what flows in carries Sides::inflow's).
enum class SideType { Periodic, Wall, Shared, Open };

struct Sides {
  std::array<SideType, 6> side{SideType::Wall, SideType::Wall, SideType::Wall,
                               SideType::Wall, SideType::Wall, SideType::Wall};
  /// Per side (index 2 * axis + s): the fractions of the fluid entering through an Open side, one
  /// per phase, summing to 1; empty: the boundary cell's own (zero gradient).
  std::array<std::vector<double>, 6> inflow;
  SideType at(int axis, int s) const { return side[static_cast<std::size_t>(2 * axis + s)]; }
  static Sides allPeriodic() {
    Sides s;
    s.side.fill(SideType::Periodic);
    return s;
  }
};

/// Ghosts of a cell field along each axis in order x, y, z over the whole extent of the other axes
/// (so edges and corners are consistent): Periodic copies the other end of this box, Wall mirrors
/// the first two cells (ghost -1 = cell 0, ghost -2 = cell 1: zero normal gradient), Open repeats
/// the first cell in both layers, Shared is left alone (parallel::fillGhosts fills it first).
void fillCellGhosts(Field& f, const Sides& sides);

/// Fills the ghosts of the listed cell fields (all of one box). One box: fillCellGhosts on each;
/// a decomposed grid: parallel::fillGhosts of the list, then fillCellGhosts.
using GhostFill = std::function<void(const std::vector<Field*>&)>;

struct TransportSettings {
  /// C of the compression velocity u_c = C |phi_f| n_f (Rusche 2002; OpenFOAM's cAlpha); 0 = off.
  double compression = 1.0;
  /// Lax-Wendroff high-order flux in the correction (true), or none (false: first-order upwind only).
  bool highOrder = true;
};

/// One box's work arrays of a phase-fraction step (reused between steps).
class PhaseTransport {
 public:
  PhaseTransport() = default;
  PhaseTransport(const CartesianGrid& box, int phases);

  int phases() const { return phases_; }

  /// Stage 1. alpha: the N fractions with ghosts filled; eps: the void fraction at the start of the
  /// step with ghosts filled; flux[a]: the superficial face velocity eps_f u_f along axis a (m/s,
  /// face fields of the box, its upper face included). Computes the upwind and the correction
  /// fluxes of every face of the box, the upwind solution and the limiter factors R+/R- of the
  /// box's cells; the caller then fills the ghosts of limiterFields().
  void computeFluxes(const std::vector<Field>& alpha, const Field& eps, const std::array<const Field*, 3>& flux,
                     double dt, const Sides& sides, const TransportSettings& settings);
  /// After applyLimitedFluxes: the volume flow of phase i out of the domain through side s of axis
  /// (m^3/s, negative for inflow), summed over the ranks (collective: every rank calls it; a Shared
  /// side adds nothing). The outflow of each phase through an outlet, and the balance of its volume.
  double boundaryOutflow(int phase, int axis, int s, const Sides& sides) const;
  /// The fields whose ghosts must be filled between the stages (R+ and R- of every phase).
  std::vector<Field*> limiterFields();
  /// Stage 2: Zalesak's face factors from the cells' R+/R-, the phases' corrections made to sum to
  /// zero on every face, the update of eps*alpha_i and the renormalisation by their sum. Leaves
  /// the ghosts of alpha unfilled.
  void applyLimitedFluxes(std::vector<Field>& alpha);

  /// After computeFluxes: the upwind flux F^L_i = phi_f alpha_i,up of phase i along axis (m/s) on
  /// the faces of the box (0 .. n along the axis).
  const Field& upwindFlux(int phase, int axis) const { return low_[static_cast<std::size_t>(3 * phase + axis)]; }
  /// Transported void fraction eps* = eps - dt div(phi) of the last step (interior cells).
  const Field& transportedVoidFraction() const { return epsStar_; }

 private:
  CartesianGrid box_;
  int phases_ = 0;
  double dt_ = 0.0;
  Field epsOld_, epsStar_;
  std::vector<Field> low_, anti_;   // per phase and axis: index 3 * phase + axis (face fields)
  std::vector<Field> qLow_;         // per phase: upwind eps*alpha after the step
  std::vector<Field> rPlus_, rMinus_;
  std::vector<Field> gradient_;     // per phase and axis: cell-centred d alpha / dx_a
};

/// One step of the phase fractions on one box: fill(alpha), stage 1, fill(limiters), stage 2,
/// fill(alpha). The ghosts of alpha are filled on return.
void advance(PhaseTransport& work, std::vector<Field>& alpha, const Field& eps, const std::array<const Field*, 3>& flux,
             double dt, const Sides& sides, const TransportSettings& settings, const GhostFill& fill);

/// advance() in m equal substeps, m the smallest count that keeps the outflow Courant number of a
/// substep at or below courantLimit (with the smaller of eps and the step's transported eps), the
/// same on every rank. Each substep starts from the previous one's transported void fraction eps*
/// (ghosts filled by `fill`), so eps goes linearly from eps to eps - dt div(phi) and every phase
/// stays conserved (MULES' sub-cycling, nAlphaSubCycles, chosen from the Courant number). Returns m.
/// afterSubstep(h), if given, runs after each substep of length h (boundaryOutflow of that substep).
int advanceSubcycled(PhaseTransport& work, std::vector<Field>& alpha, const Field& eps,
                     const std::array<const Field*, 3>& flux, double dt, const Sides& sides,
                     const TransportSettings& settings, const GhostFill& fill, double courantLimit = 0.5,
                     const std::function<void(double substep)>& afterSubstep = {});

/// The ghost fill of one box with no neighbours (fillCellGhosts with `sides` on every field).
GhostFill singleBoxFill(const Sides& sides);
/// The sides of this rank's box of a decomposition: Shared where it says so, Periodic where one
/// rank wraps an axis onto itself, Wall on the domain's other sides.
Sides boxSides(const parallel::Decomposition& d);
/// The ghost fill of this rank's box: parallel::fillGhosts of the listed fields (one message per
/// neighbour for all of them), then fillCellGhosts with boxSides(d). `d` must outlive the fill.
GhostFill decomposedFill(const parallel::Decomposition& d);
/// The same with the box's own sides (boxSides(d) with Open inlets and outlets set by the caller).
GhostFill decomposedFill(const parallel::Decomposition& d, const Sides& sides);

/// Largest outflow Courant number sum_faces max(0, phi_out) dt / (eps h) over the cells of every
/// box (maxAcrossRanks): the upwind part, hence the whole step, is bounded for a value <= 1.
double maxCourant(const Field& eps, const std::array<const Field*, 3>& flux, double dt);

/// Volume of phase i, sum over the interior cells of eps alpha_i V, summed across the ranks.
double phaseVolume(const Field& alpha, const Field& eps, const SumPolicy& policy = {});
/// Largest |sum_i alpha_i - 1| over the interior cells of every box (maxAcrossRanks).
double maxSumError(const std::vector<Field>& alpha);
/// Smallest and largest alpha of the interior cells (minimum as -max(-a)), across the ranks.
std::array<double, 2> fractionRange(const Field& alpha);

/// Mixture value of a cell, seed 002 eqs. 3-4 (lines 320-322): sum_i alpha_i value_i (density
/// rho_f = sum alpha_i rho_i, viscosity mu_f = sum alpha_i mu_i).
inline double mixtureValue(const double* alpha, const double* value, int phases) {
  double s = 0.0;
  for (int i = 0; i < phases; ++i) s += alpha[i] * value[i];
  return s;
}
/// The mixture field (seed 002 eqs. 3-4) over the box, ghosts included: out = sum_i alpha_i value_i.
void mixtureField(const std::vector<Field>& alpha, const std::vector<double>& value, Field& out);

}  // namespace gf::vof
