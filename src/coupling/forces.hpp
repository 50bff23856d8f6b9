#pragma once
// Fluid forces on one particle as pure functions (SI units). Which of them act on the particle
// and which are given back to the fluid depends on model A / B (docs/coupling.md, seed 000
// l. 849-956, seed 001 eqs. 26-32). Particle diameter d, volume V, relative velocity
// slip = u_f - u_p (interstitial fluid velocity at the particle minus particle velocity).
#include <cmath>
#include <numbers>

#include "core/vec3.hpp"

namespace gf::coupling::force {

inline double sphereVolume(double d) { return std::numbers::pi / 6.0 * d * d * d; }

/// Drag, F = beta_p (u_f - u_p), beta_p = 3 pi mu d f (drag_law.hpp).
inline Vec3 drag(double beta, const Vec3& slip) { return beta * slip; }

/// Pressure-gradient force of the undisturbed flow, F = -V grad p (seed 000 eq. 5.19).
inline Vec3 pressureGradient(double volume, const Vec3& gradP) { return -volume * gradP; }

/// Viscous force of the undisturbed flow, F = V div(tau) (the particle feels the stress divergence
/// of the fluid it displaces; seed 000 eq. 5.20 and seed 001 eq. 28 write -V div(tau) with
/// CFDEM's field divTau = -div(tau)).
inline Vec3 viscousStress(double volume, const Vec3& divTau) { return volume * divTau; }

/// Buoyancy for a fluid pressure without its hydrostatic part, F = -rho_f V g (seed 001 eq. 26).
inline Vec3 buoyancy(double fluidDensity, double volume, const Vec3& gravity) { return -fluidDensity * volume * gravity; }

/// Virtual (added) mass, F = C_vm rho_f V (D u_f/Dt - d u_p/dt), approximated on the coupling
/// interval dt by the change of the slip seen by the particle: C_vm rho_f V (slip - slipOld)/dt
/// (as CFDEM virtualMassForce). C_vm = 0.5 for a sphere.
inline Vec3 virtualMass(double coefficient, double fluidDensity, double volume, const Vec3& slip, const Vec3& slipOld,
                        double dt) {
  return (coefficient * fluidDensity * volume / dt) * (slip - slipOld);
}

/// Mei (1992) correction of the Saffman lift, f = F_L / F_L,Saffman:
///   Re <= 40: (1 - 0.3314 sqrt(b)) exp(-Re/10) + 0.3314 sqrt(b);  Re > 40: 0.0524 sqrt(b Re)
///   b = Re_w / (2 Re),  Re = rho |slip| d / mu,  Re_w = rho |omega| d^2 / mu.
inline double meiCorrection(double re, double reShear) {
  if (re <= 0.0) return 1.0;
  const double b = 0.5 * reShear / re;
  const double sb = std::sqrt(b);
  return re <= 40.0 ? (1.0 - 0.3314 * sb) * std::exp(-0.1 * re) + 0.3314 * sb : 0.0524 * std::sqrt(b * re);
}

/// Saffman (1965) shear lift with Mei's correction:
///   F = 1.615 d^2 sqrt(rho mu / |omega|) f_Mei (slip x omega),  omega = curl u_f.
/// (Saffman: 6.46 mu a^2 U sqrt(|omega|/nu) with a = d/2.)
inline Vec3 saffmanMeiLift(double fluidDensity, double viscosity, double d, const Vec3& slip, const Vec3& vorticity) {
  const double w = norm(vorticity);
  const double s = norm(slip);
  if (w <= 0.0 || s <= 0.0) return {};
  const double re = fluidDensity * s * d / viscosity;
  const double reShear = fluidDensity * w * d * d / viscosity;
  return (1.615 * d * d * std::sqrt(fluidDensity * viscosity / w) * meiCorrection(re, reShear)) * cross(slip, vorticity);
}

/// Relative rotation of a particle, omega_p - 1/2 curl u_f.
inline Vec3 relativeRotation(const Vec3& angularVelocity, const Vec3& vorticity) {
  return angularVelocity - 0.5 * vorticity;
}

/// Magnus lift at low Re (Rubinow & Keller 1961): F = pi a^3 rho_f Omega x (u_p - u_f)
///   = (pi/8) d^3 rho_f (omega_p - 1/2 curl u_f) x (-slip).
inline Vec3 magnusLift(double fluidDensity, double d, const Vec3& relativeOmega, const Vec3& slip) {
  return (std::numbers::pi / 8.0 * d * d * d * fluidDensity) * cross(relativeOmega, -slip);
}

/// Torque on a sphere rotating relative to the fluid, Stokes regime: T = -pi mu d^3 (omega_p - 1/2 curl u_f).
inline Vec3 rotationalTorque(double viscosity, double d, const Vec3& relativeOmega) {
  return (-std::numbers::pi * viscosity * d * d * d) * relativeOmega;
}

}  // namespace gf::coupling::force
