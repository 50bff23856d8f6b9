#include "coupling/drag/koch_hill.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using KochHillDrag = DragLawOf<&drag::kochHill>;
GF_REGISTER_MODEL(DragLaw, KochHillDrag, "koch_hill",
                  "Koch & Hill (2001) lattice-Boltzmann fit, van Buijtenen (2011) form: f = eps^2 (F0 + F3 Re/2)")
}  // namespace gf::coupling
