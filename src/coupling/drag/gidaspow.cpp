#include "coupling/drag/gidaspow.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using GidaspowDrag = DragLawOf<&drag::gidaspow>;
GF_REGISTER_MODEL(DragLaw, GidaspowDrag, "gidaspow",
                  "Gidaspow (1994): Ergun for eps < 0.8, Wen-Yu (C_D eps^-2.65) for eps >= 0.8 (discontinuous at 0.8)")
}  // namespace gf::coupling
