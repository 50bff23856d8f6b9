#pragma once
// Linear spring-dashpot (seed 000 Appendix B eq. B.5: F = k d + gamma v), with history.
//   F_n = k_n d - gamma_n v_n,  gamma_n = alpha sqrt(m* k_n)  (alpha from e, restitution_damping.hpp)
//   F_t = -k_t xi - gamma_t v_t, |F_t| <= mu F_n (Cundall & Strack 1979)
#include <cmath>
#include <numbers>

namespace gf::dem::hooke {

inline double dampingCoefficient(double alpha, double stiffness, double effectiveMass) {
  return alpha * std::sqrt(effectiveMass * stiffness);
}
/// Contact duration of the (unclamped) damped linear oscillator: pi / sqrt(k/m - (gamma/2m)^2).
inline double contactDuration(double stiffness, double effectiveMass, double gamma) {
  const double w2 = stiffness / effectiveMass - 0.25 * gamma * gamma / (effectiveMass * effectiveMass);
  return std::numbers::pi / std::sqrt(w2);
}

}  // namespace gf::dem::hooke
