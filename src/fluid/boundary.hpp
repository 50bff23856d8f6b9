#pragma once
// Boundary conditions of the fluid solver, one per box face (x_min, x_max, y_min, ...), and the
// ghost-layer filling that applies them to staggered velocity and cell-centred fields.
#include <array>
#include <memory>
#include <string>

#include "core/grid.hpp"
#include "core/params.hpp"
#include "parallel/decomposition.hpp"

namespace gf::fluid {

/// Shared: a side of this rank's box inside the domain on a decomposed grid (the ghosts beyond it
/// are the neighbour rank's values, filled by parallel::fillGhosts; no condition applies there).
enum class BoundaryType { Wall, Slip, Inlet, PressureOutlet, Outflow, Periodic, Shared };

struct BoundarySide {
  BoundaryType type = BoundaryType::Wall;
  Vec3 velocity;           // wall velocity (tangential) or inlet velocity, m/s
  bool parabolic = false;  // inlet: parabolic profile with peak `velocity` instead of uniform
  double pressure = 0.0;   // pressure outlet, Pa
  bool scalarFixed = false;
  double scalarValue = 0.0;  // Dirichlet value of the passive scalar where scalarFixed
  double rampTime = 0.0;     // inlet/wall velocity multiplied by min(1, t / rampTime); 0 = no ramp
  bool superficial = true;   // inlet: `velocity` is superficial (face flux eps_f u_f = U), not interstitial
  std::string phase;         // fluid.vof: the phase entering through this side (empty: fluid.vof.inflow_phase)
};

/// Factor of a side's prescribed velocity at time t: min(1, t / rampTime) (1 without ramp).
inline double rampFactor(const BoundarySide& s, double t) {
  return s.rampTime > 0.0 ? (t >= s.rampTime ? 1.0 : (t > 0.0 ? t / s.rampTime : 0.0)) : 1.0;
}

inline int sideIndex(int axis, int side) { return 2 * axis + side; }
/// The case-file name of side s = sideIndex(axis, side): x_min, x_max, y_min, y_max, z_min, z_max.
const char* sideName(int s);
inline bool isOutlet(BoundaryType t) { return t == BoundaryType::PressureOutlet || t == BoundaryType::Outflow; }

struct Boundaries {
  std::array<BoundarySide, 6> side;
  double time = 0.0;  // s: time at which prescribed velocities are evaluated (ramps); set by the solver
  /// Cell void fraction (ghosts filled) for superficial inlets: face velocity = U / eps_f with
  /// eps_f the mean of the first cell and its ghost (the face eps of the continuity equation).
  /// Null: eps_f = 1. Set by the solver before every use.
  const Field* voidFraction = nullptr;
  /// On a decomposed grid (decompose()): the ranks' layout, the conditions of the domain's own
  /// sides (side[] then holds Shared where this rank's box meets a neighbour), and the domain's
  /// grid (origin, cells) for the inlet profiles. Without: side[] are the domain's sides.
  std::shared_ptr<const parallel::Decomposition> decomposition;
  std::array<BoundaryType, 6> domainType{};  // (read through domainSide())
  Vec3 domainOrigin;
  std::array<int, 3> domainCells{0, 0, 0};

  const BoundarySide& at(int axis, int s) const { return side[sideIndex(axis, s)]; }
  /// This rank wraps the axis itself (periodic, one rank along it): its ghosts copy its own other end.
  bool periodic(int axis) const { return side[sideIndex(axis, 0)].type == BoundaryType::Periodic; }
  /// The condition of the domain's side (on a decomposed grid, also where this rank's side is Shared).
  BoundaryType domainSide(int axis, int s) const {
    return decomposition ? domainType[sideIndex(axis, s)] : side[sideIndex(axis, s)].type;
  }
  /// The domain is periodic along the axis (on one rank, or split among several).
  bool domainPeriodic(int axis) const { return domainSide(axis, 0) == BoundaryType::Periodic; }
  bool shared(int axis, int s) const { return side[sideIndex(axis, s)].type == BoundaryType::Shared; }
  /// A side with a boundary condition of the domain (neither periodic nor shared with a neighbour).
  bool physical(int axis, int s) const {
    const BoundaryType t = side[sideIndex(axis, s)].type;
    return t != BoundaryType::Periodic && t != BoundaryType::Shared;
  }
  /// Whether ghost fills exchange values with neighbour ranks (a decomposition of several ranks).
  bool distributed() const { return decomposition && decomposition->distributed(); }
  /// The sides of rank d's box: Shared where d says so, the domain's condition elsewhere; d is
  /// kept, and the grid origin and cells of the whole domain.
  void decompose(std::shared_ptr<const parallel::Decomposition> d, const Vec3& origin, const std::array<int, 3>& cells);

  /// Reads section 'boundaries' (x_min ... z_max); periodic directions come from the domain.
  /// In 2D (one cell in z) the z sides are periodic whatever the file says.
  static Boundaries read(Params& fluid, const std::array<bool, 3>& periodic, bool twoD);
};

/// How ghosts are filled: with the boundary values, or with zero boundary data (the linear,
/// homogeneous part of the condition, used for increments inside Krylov solvers).
enum class GhostMode { Full, Homogeneous };

/// The part of a field's ghost fill done by one member of a thread team that owns the z planes
/// kBegin <= k < kEnd of the field (kEnd < 0: all): the x and y ghosts of those planes, and the z
/// ghosts of the min / max side where lowZ / highZ (with the x and y ghosts of those ghost planes).
/// The member owning lowZ / highZ must own the first / last `ghosts` planes (the z ghosts are
/// filled from them after its own x and y ghosts), and z must not be periodic unless one member
/// owns everything. Every point gets the value of the whole fill (the same order per point).
/// threaded: may start an OpenMP team for large faces (false inside a team).
struct GhostPlanes {
  int kBegin = 0, kEnd = -1;
  bool lowZ = true, highZ = true;
  bool threaded = true;
  /// On a decomposed grid, a fill of all planes first exchanges the ghosts across the cuts;
  /// false: the caller has just done so (several fields in one exchange).
  bool exchange = true;
};

/// Normal velocity at an inlet face point (profile evaluated at the face centre).
double inletNormalVelocity(const Boundaries& bc, int axis, int side, const CartesianGrid& g, const Vec3& faceCentre);

/// Ghosts (and prescribed boundary faces) of velocity component `c` (face field along c).
/// The axes are filled in order x, y, z (a later axis overwrites the edge ghosts it shares with
/// an earlier one); firstAxis > 0 refills only the axes >= firstAxis, for a field whose ghosts
/// of the earlier axes are still those of a full fill of the same interior values.
void fillVelocityGhosts(Field& u, int c, const Boundaries& bc, GhostMode mode, int firstAxis = 0);
/// fillVelocityGhosts on the planes of one team member (GhostPlanes).
void fillVelocityGhostsPlanes(Field& u, int c, const Boundaries& bc, GhostMode mode, const GhostPlanes& planes,
                              int firstAxis = 0);

/// First axis with a side whose velocity ghosts depend on more than the interior velocities
/// (inlets: time ramp, eps of superficial inlets; walls with a velocity: time ramp); 3 if none.
int firstTimeDependentVelocityAxis(const Boundaries& bc);

/// The part of fillVelocityGhosts(u, c, bc, Full) that the 7-point momentum stencil reads at the
/// momentum unknowns: the first ghost layer of the interior grid lines (no edge or corner ghosts,
/// no second layer) and the duplicate last face of a periodic normal axis. Non-periodic normal
/// boundary faces are left alone (the solver keeps them). Same values as the full fill there;
/// for iterations whose sweeps keep the boundary faces (Chebyshev sweeps), followed by a full fill.
void fillVelocityStencilGhosts(Field& u, int c, const Boundaries& bc);

/// fillVelocityStencilGhosts for one member of a thread team that owns the z planes
/// kBegin <= k < kEnd: the x and y ghosts of those planes, and the z ghosts of the min / max side
/// where lowZ / highZ (the member owning the first / last two planes). z must not be periodic.
/// Runs on the calling thread.
void fillVelocityStencilGhostsSlab(Field& u, int c, const Boundaries& bc, int kBegin, int kEnd, bool lowZ,
                                   bool highZ);

/// Kinds of cell-centred ghost fill.
/// PeriodicOnly: wrap-around ghosts of periodic axes only (fields read at momentum faces only:
/// their non-periodic ghosts are never used).
enum class CellGhostKind { ZeroGradient, Pressure, PressureIncrement, Scalar, PeriodicOnly };
void fillCellGhosts(Field& f, const Boundaries& bc, CellGhostKind kind);
/// fillCellGhosts on the planes of one team member (GhostPlanes).
void fillCellGhostsPlanes(Field& f, const Boundaries& bc, CellGhostKind kind, const GhostPlanes& planes);

}  // namespace gf::fluid
