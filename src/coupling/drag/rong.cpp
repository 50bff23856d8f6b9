#include "coupling/drag/rong.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using RongDrag = DragLawOf<&drag::rong>;
GF_REGISTER_MODEL(DragLaw, RongDrag, "rong",
                  "Rong et al. (2013): Dallavalle C_D times eps^-chi(eps, Re), fitted to lattice-Boltzmann data")
}  // namespace gf::coupling
