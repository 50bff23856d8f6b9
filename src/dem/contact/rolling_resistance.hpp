#pragma once
// Rolling resistance torques (Ai, Chen, Rotter & Ooi 2011, Powder Technol. 206:269).
//   constant directional torque (model A): M_r = -mu_r R* F_n w_t/|w_t|
//   elastic-plastic spring-dashpot (EPSD, model C): k_r = 2.25 k_n mu_r^2 R*^2 (eq. 17),
//     M_k <- M_k - k_r w_t dt, |M_k| <= mu_r R* F_n (eq. 16), damping C_r = 2 eta_r sqrt(I_r k_r)
//     (eq. 19), applied only while |M_k| < M_max; I_r = 1/(1/(I_i+m_i R_i^2) + 1/(I_j+m_j R_j^2)).
#include "core/vec3.hpp"

namespace gf::dem::rolling {

inline Vec3 constantTorque(double rollingFriction, double effectiveRadius, double normalForce,
                           const Vec3& tangentialAngularVelocity) {
  const double w = norm(tangentialAngularVelocity);
  if (w <= 0.0) return {};
  return (-rollingFriction * effectiveRadius * normalForce / w) * tangentialAngularVelocity;
}

inline double epsdStiffness(double normalStiffness, double rollingFriction, double effectiveRadius) {
  return 2.25 * normalStiffness * rollingFriction * rollingFriction * effectiveRadius * effectiveRadius;
}

/// Updates the spring torque `springTorque` (history) and returns the total rolling torque on i.
inline Vec3 epsdTorque(Vec3& springTorque, double stiffness, double maxTorque, double dampingRatio,
                       double rollingInertia, const Vec3& tangentialAngularVelocity, double dt) {
  springTorque -= (stiffness * dt) * tangentialAngularVelocity;
  const double m = norm(springTorque);
  if (m > maxTorque) {
    springTorque *= maxTorque / m;
    return springTorque;
  }
  const double damping = 2.0 * dampingRatio * std::sqrt(rollingInertia * stiffness);
  return springTorque - damping * tangentialAngularVelocity;
}

}  // namespace gf::dem::rolling
