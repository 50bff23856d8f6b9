#include "coupling/drag/schiller_naumann.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
using SchillerNaumannDrag = DragLawOf<&drag::schillerNaumann>;
GF_REGISTER_MODEL(DragLaw, SchillerNaumannDrag, "schiller_naumann",
                  "Schiller-Naumann (1933) isolated-sphere drag, C_D = 24/Re (1 + 0.15 Re^0.687); no voidage correction")
}  // namespace gf::coupling
