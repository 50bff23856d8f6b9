#include "coupling/drag/dallavalle.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using DallavalleDrag = DragLawOf<&drag::dallavalle>;
GF_REGISTER_MODEL(DragLaw, DallavalleDrag, "dallavalle",
                  "Dallavalle (1948) isolated-sphere drag, C_D = (0.63 + 4.8/sqrt(Re))^2; no voidage correction")
}  // namespace gf::coupling
