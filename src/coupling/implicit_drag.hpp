#pragma once
// Semi-implicit drag in the particle update (seed 000 eq. 5.26, "case III"): with beta_p from the
// last coupling step and the fluid velocity u_f at the particle held over the DEM substeps,
//   m (v_new - v_old)/dt = F_other + beta_p (u_f - v_new)
//   =>  v_new = (v_old + dt (F_other + beta_p u_f)/m) / (1 + dt beta_p / m).
// Unconditionally stable in dt (the explicit update needs dt < 2 m / beta_p = 2 tau_p). For the
// DEM integrator: Coupler::dragCoefficients() and slipVelocities() give beta_p and u_f - v_coupling;
// F_other is then the particle's force without the drag (externalForce - beta_p (u_f - v_coupling)).
#include "core/vec3.hpp"

namespace gf::coupling {

inline Vec3 semiImplicitDragVelocity(const Vec3& velocity, const Vec3& fluidVelocity, double dragCoefficient,
                                     double mass, const Vec3& otherForce, double dt) {
  const double a = dt * dragCoefficient / mass;
  return (velocity + (dt / mass) * otherForce + a * fluidVelocity) / (1.0 + a);
}

}  // namespace gf::coupling
