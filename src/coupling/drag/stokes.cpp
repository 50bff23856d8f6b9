#include "coupling/drag/stokes.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using StokesDrag = DragLawOf<&drag::stokes>;
GF_REGISTER_MODEL(DragLaw, StokesDrag, "stokes", "Stokes drag of an isolated sphere, F = 3 pi mu d (u - v); no voidage correction")
}  // namespace gf::coupling
