#pragma once
// Law-level settling and packed-bed relations (no fluid solver involved), used by the tests and
// as reference values for the coupled cases. Assumptions are in each comment.
#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {

struct SettlingFluid {
  double density;    // kg/m^3
  double viscosity;  // Pa s
};

/// Terminal velocity (m/s) of one sphere in quiescent fluid (hydrostatic pressure) from the law,
/// evaluated at void fraction eps (1: isolated):  3 pi mu d f(Re, eps) v = (rho_p - rho_f) V g,
/// solved by bisection.
double terminalVelocity(const DragLaw& law, const SettlingFluid& fluid, double d, double particleDensity, double g,
                        double eps = 1.0);

/// Settling velocity (m/s, relative to the container) of a homogeneous monodisperse suspension at
/// void fraction eps, zero net volume flux (eps u_f + (1 - eps) v = 0) and model-A forces:
/// steady, the drag balances the weight less the mixture pressure gradient,
///   beta_p (u_f - v) = eps (rho_p - rho_f) V g,  slip = v / eps  (seed 000 eqs. 5.7, 5.10).
double hinderedSettlingVelocity(const DragLaw& law, const SettlingFluid& fluid, double d, double particleDensity,
                                double g, double eps);

/// Pressure gradient (Pa/m) through a fixed bed of spheres at void fraction eps and superficial
/// velocity U (model A, steady, uniform): eps dp/dx = n F_d, n = (1-eps)/V_p, F_d = beta_p U/eps.
double packedBedPressureGradient(const DragLaw& law, const SettlingFluid& fluid, double d, double eps,
                                 double superficialVelocity);

/// Ergun (1952): dp/dx = 150 mu (1-eps)^2 U / (eps^3 d^2) + 1.75 rho (1-eps) U^2 / (eps^3 d).
double ergunPressureGradient(const SettlingFluid& fluid, double d, double eps, double superficialVelocity);

}  // namespace gf::coupling
