#pragma once
// Damping coefficient that gives a prescribed coefficient of restitution.
//
// Both normal laws are  m* d'' = -k d^p - alpha sqrt(m* k) d^q d'  with the force clamped at zero
// (no tensile contact force): Hooke p = 1, q = 0 (seed 000 eq. B.5, F = k d + gamma v);
// Hertz p = 3/2, q = 1/4 (Tsuji et al. 1992, Powder Technol. 71:239). Scaling d = d0 x,
// t = T tau with m* d0/T^2 = k d0^p and v0 = d0/T gives  x'' = -max(0, x^p + alpha x^q x'),
// x(0) = 0, x'(0) = 1, so the restitution e = -x'(end) depends on alpha only. e(alpha) is computed
// once by RK4 and inverted by bisection: the measured restitution equals the input e, also with
// the clamp (where the closed form ln e/sqrt(ln^2 e + pi^2) is off by several per cent).
namespace gf::dem {

/// Restitution of one collision for a given alpha (exponents p, q as above).
double restitutionForDamping(double alpha, double p, double q);
/// Inverse of restitutionForDamping; e in (0, 1]. Cached per (e, p, q).
double dampingForRestitution(double e, double p, double q);

}  // namespace gf::dem
