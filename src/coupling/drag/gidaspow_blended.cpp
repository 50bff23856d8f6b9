#include "coupling/drag/drag_law.hpp"
#include "coupling/drag/gidaspow.hpp"

namespace gf::coupling {
using GidaspowBlendedDrag = DragLawOf<&drag::gidaspowBlended>;
GF_REGISTER_MODEL(DragLaw, GidaspowBlendedDrag, "gidaspow_blended",
                  "Huilin-Gidaspow (2003): Ergun and Wen-Yu blended by 1/2 + atan(262.5 (phi - 0.2))/pi (continuous)")
}  // namespace gf::coupling
