#pragma once
// Hertz normal force with Tsuji-type damping and Mindlin tangential stiffness, as pure functions.
//   F_n = k_hz d^(3/2) - alpha sqrt(m* k_hz) d^(1/4) v_n,  k_hz = 4/3 E* sqrt(R*)
//     (Hertz 1882 / Johnson 1985 eq. 4.22; damping form Tsuji et al. 1992)
//   k_t = 8 G* sqrt(R* d)                         (Mindlin 1949; Di Renzo & Di Maio 2004 eq. 14)
//   gamma_t = gamma_n sqrt(k_t / (dF_n/dd)) = gamma_n sqrt(4 G*/E*)   (LIGGGHTS hertz damping)
#include <cmath>

namespace gf::dem::hertz {

inline double stiffnessPrefactor(double effectiveYoungs, double effectiveRadius) {
  return 4.0 / 3.0 * effectiveYoungs * std::sqrt(effectiveRadius);
}
inline double elasticForce(double kHertz, double overlap) { return kHertz * overlap * std::sqrt(overlap); }
inline double dampingCoefficient(double alpha, double kHertz, double effectiveMass, double overlap) {
  return alpha * std::sqrt(effectiveMass * kHertz * std::sqrt(overlap));
}
inline double tangentialStiffness(double effectiveShear, double effectiveRadius, double overlap) {
  return 8.0 * effectiveShear * std::sqrt(effectiveRadius * overlap);
}
/// Linearised normal stiffness dF_n/dd = 2 E* sqrt(R* d).
inline double normalTangentStiffness(double effectiveYoungs, double effectiveRadius, double overlap) {
  return 2.0 * effectiveYoungs * std::sqrt(effectiveRadius * overlap);
}
/// Duration of an elastic Hertz impact (Johnson 1985 eq. 11.24): t = 2.9432 d_max / v,
/// d_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5).
inline double elasticContactDuration(double effectiveMass, double effectiveYoungs, double effectiveRadius,
                                     double impactSpeed) {
  const double maxOverlap = std::pow(15.0 * effectiveMass * impactSpeed * impactSpeed /
                                         (16.0 * effectiveYoungs * std::sqrt(effectiveRadius)),
                                     0.4);
  return 2.9432 * maxOverlap / impactSpeed;
}

}  // namespace gf::dem::hertz
