#include "coupling/drag/syamlal_obrien.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using SyamlalObrienDrag = DragLawOf<&drag::syamlalObrien>;
GF_REGISTER_MODEL(DragLaw, SyamlalObrienDrag, "syamlal_obrien",
                  "Syamlal & O'Brien (1987): Dallavalle C_D at Re/V_r with the Garside-Al-Dibouni velocity ratio V_r")
}  // namespace gf::coupling
