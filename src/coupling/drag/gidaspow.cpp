#include "coupling/drag/gidaspow.hpp"

#include "coupling/drag/drag_law.hpp"
#include "coupling/loops.hpp"

namespace gf::coupling::drag {

GF_VECTOR_CLONES
void gidaspowBlock(const double* re, const double* eps, double* f, int n) {
  using Double8 = double __attribute__((vector_size(64)));
  int i = 0;
  for (; i + 8 <= n; i += 8) {
    Double8 r, e;
    __builtin_memcpy(&r, re + i, sizeof r);
    __builtin_memcpy(&e, eps + i, sizeof e);
    const Double8 phi = 1.0 - e;
    const Double8 ergun8 = 25.0 * phi / (3.0 * e) + 1.75 * r / 18.0;  // as ergun()
    __builtin_memcpy(f + i, &ergun8, sizeof ergun8);
  }
  for (; i < n; ++i) f[i] = ergun(re[i], eps[i]);
  for (i = 0; i < n; ++i)
    if (!(eps[i] < kGidaspowSwitchVoidFraction)) f[i] = wenYu(re[i], eps[i]);
}

}  // namespace gf::coupling::drag

namespace gf::coupling {
using GidaspowDrag = DragLawOf<&drag::gidaspow>;
GF_REGISTER_MODEL(DragLaw, GidaspowDrag, "gidaspow",
                  "Gidaspow (1994): Ergun for eps < 0.8, Wen-Yu (C_D eps^-2.65) for eps >= 0.8 (discontinuous at 0.8)")
}  // namespace gf::coupling
