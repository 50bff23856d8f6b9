#pragma once
// Dallavalle (1948) drag of an isolated sphere, C_D = (0.63 + 4.8/sqrt(Re))^2 (seed 001 eq. 15),
// interstitial slip Reynolds number, no voidage correction.
#include "coupling/drag/single_sphere.hpp"

namespace gf::coupling::drag {
inline double dallavalle(double re, double /*eps*/) { return dallavalleFactor(re); }
}  // namespace gf::coupling::drag
