#include "coupling/drag/di_felice.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using DiFeliceDrag = DragLawOf<&drag::diFelice>;
GF_REGISTER_MODEL(DragLaw, DiFeliceDrag, "di_felice",
                  "Di Felice (1994): Dallavalle C_D times eps^-chi, chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2/2)")
}  // namespace gf::coupling
