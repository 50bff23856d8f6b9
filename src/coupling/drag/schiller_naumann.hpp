#pragma once
// Schiller & Naumann (1933) drag of an isolated sphere, interstitial slip Reynolds number, no
// voidage correction (CFDEM SchillerNaumannDrag): f = 1 + 0.15 Re^0.687 (Re < 1000), 0.44 Re/24.
#include "coupling/drag/single_sphere.hpp"

namespace gf::coupling::drag {
inline double schillerNaumann(double re, double /*eps*/) { return schillerNaumannFactor(re); }
}  // namespace gf::coupling::drag
