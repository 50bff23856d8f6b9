#pragma once
// Void fraction on the faces of a staggered velocity control volume (MAC grid), as the VANS
// viscous term div(eps tau) needs it (seed 000, volume-averaged momentum equation; seed 001 eq. for
// model A/B): the control volume of component c lies between cells cm and cc (cm = cc - stride_c).
#include <cstddef>

namespace gf::fluid {

struct FaceVoidFractions {
  double plus, minus;  // on the + and - faces normal to axis d
};

/// Along d == c the faces are the cell centres cc and cm; across (d != c) each face is an edge of
/// four cells, whose mean it takes. strideD: flat stride of axis d.
[[gnu::always_inline]] inline FaceVoidFractions controlVolumeFaceEps(const double* E, std::size_t cc, std::size_t cm,
                                                                     std::ptrdiff_t strideD, bool alongC) {
  if (alongC) return {E[cc], E[cm]};
  return {0.25 * (E[cc] + E[cm] + E[cc + strideD] + E[cm + strideD]),
          0.25 * (E[cc] + E[cm] + E[cc - strideD] + E[cm - strideD])};
}

}  // namespace gf::fluid
