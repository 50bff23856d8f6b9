#include "coupling/drag/beetstra.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using BeetstraDrag = DragLawOf<&drag::beetstra>;
GF_REGISTER_MODEL(DragLaw, BeetstraDrag, "beetstra",
                  "Beetstra, van der Hoef & Kuipers (2007) monodisperse lattice-Boltzmann fit, F_d = 3 pi mu d eps F* (u - v)")
}  // namespace gf::coupling
