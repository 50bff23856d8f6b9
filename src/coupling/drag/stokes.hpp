#pragma once
// Stokes drag of an isolated sphere, F = 3 pi mu d (u_f - u_p) (seed 003 eq. 3.9). No voidage
// correction; valid for Re << 1 and dilute suspensions only.
namespace gf::coupling::drag {
inline double stokes(double /*re*/, double /*eps*/) { return 1.0; }
}  // namespace gf::coupling::drag
