#pragma once
// Ghost-layer exchange of grid fields between the ranks of a decomposed grid (parallel/decomposition.hpp):
//
//   fillGhosts(f, d)  copies the owners' interior points into the ghost points of their neighbours
//                     across every Shared side: faces, edges and corners, periodic wrap between
//                     ranks included.
//   sumGhosts(f, d)   the reverse: the values deposited in those ghost points are added to the
//                     owner's points, and the ghost points are set to 0 (the coupling's void
//                     fraction, force and drag deposits near a cut).
//
// Physical sides, and the Periodic sides of an axis with one rank, are left to the subsystem's own
// boundary code: run it after fillGhosts (its lines include the ghost rows of the other axes, so
// edges and corners that meet a physical side get their values from the exchanged ghosts), and
// fold deposits across such sides after sumGhosts (the exchanged ghost rows of the other axes
// then hold what was deposited beyond both sides).
//
// Ownership. Along an axis, a rank owns its cells 0..n-1. A field staggered along that axis (the
// MAC velocity component normal to the faces) has n+1 points: face 0 is the rank's own (the cut
// face belongs to the upper rank, as face 0 of a periodic axis does on one rank), and face n across
// a Shared upper side is a copy of the upper rank's face 0 (filled by fillGhosts, summed into the
// upper rank by sumGhosts). Across a Physical upper side face n is the boundary face, owned here.
//
// Per axis a point's class is -1 (a ghost below a Shared lower side), +1 (at or above the owned
// range across a Shared upper side) or 0; a point of classes d != (0,0,0) belongs to the rank at
// coords + d, the neighbour with whom it is exchanged. Along an axis of class 0 the exchanged rows
// include the ghost layers of non-Shared sides, so deposits beyond a physical or single-rank
// periodic side in a cut's ghost rows also reach the owner.
//
// Messages go to the face, edge and corner neighbours only (MPI_Isend/MPI_Irecv, one message per
// neighbour direction and call, all fields of a call packed together); no collective. On one
// rank (or with no Shared side) both verbs return without touching MPI. Each rank's box must hold
// at least `ghosts` cells (ghosts + 1 for a field staggered along the axis) along every decomposed
// axis; std::invalid_argument otherwise.
#include <initializer_list>
#include <vector>

#include "core/grid.hpp"
#include "parallel/decomposition.hpp"

namespace gf::parallel {

/// Fill the ghosts across Shared sides of f (its grid: this rank's box of d's grid).
void fillGhosts(Field& f, const Decomposition& d);
/// fillGhosts for several fields at once (one message per neighbour direction for all of them).
void fillGhosts(std::initializer_list<Field*> fields, const Decomposition& d);
void fillGhosts(const std::vector<Field*>& fields, const Decomposition& d);

/// Add the values in the ghosts across Shared sides to their owners' points, then zero those ghosts.
void sumGhosts(Field& f, const Decomposition& d);
/// sumGhosts for several fields at once.
void sumGhosts(std::initializer_list<Field*> fields, const Decomposition& d);
void sumGhosts(const std::vector<Field*>& fields, const Decomposition& d);

/// The whole grid's field `whole` (its grid: the domain's; points and ghost layers as one rank
/// holding the whole grid has them) assembled on rank 0 from every rank's `local` box: each point
/// from the rank whose class-0 points hold it (its own points, with the ghost layers beyond its
/// physical and one-rank periodic sides), so every point comes from exactly one rank; along a
/// periodic axis split among ranks the wrap-around points are copies of the other end. On the
/// other ranks `whole` is left empty. Collective (all ranks). On one rank: whole = local.
void gatherField(const Field& local, const Decomposition& d, const CartesianGrid& wholeGrid, Field& whole);
/// This rank's box of a whole-grid field, every point of `local` (ghosts included) from the
/// point of `whole` at the same global index; no communication (every rank holds `whole`).
void extractBox(const Field& whole, const Decomposition& d, Field& local);

}  // namespace gf::parallel
