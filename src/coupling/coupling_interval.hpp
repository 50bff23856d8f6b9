#pragma once
// Coupling interval criterion (seed 000, sec. 5.2, eqs. 5.22-5.30, tables 5.4-5.5).
//   Particle relaxation time  tau_p = rho_p d^2 / (18 mu) / (1 + 0.15 Re^0.687)     (eq. 5.22)
//   Re = rho_f |u - u_p| d / mu                                                     (eq. 5.23)
// Findings used here: (i) the explicit drag update is unstable when the DEM step exceeds tau_p
// (table 5.4: the explicit schemes fail for tau_p ~ dt); (ii) the coupling error is a function of
// tau_p / tau_c only (fig. 5.3), so an interval tau_c,1 validated for diameter d1 transfers to d2 by
//   tau_c,2 = (d2/d1)^2 (1 + 0.15 Re1^0.687) / (1 + 0.15 (Re1 d2/d1)^0.687) tau_c,1     (eq. 5.30)
// The accepted ratio tau_p / tau_c is a case option (coupling.min_relaxation_to_interval_ratio).
#include <string>

namespace gf::coupling {

/// Eq. 5.22.
double particleRelaxationTime(double particleDensity, double diameter, double viscosity, double reynolds);

/// Eq. 5.30: interval for diameter d2 giving the same coupling error as tau_c1 for diameter d1,
/// with the slip (hence Re1 = slip d1 / nu) of the original particle.
double scaledCouplingInterval(double couplingInterval1, double diameter1, double diameter2, double slipVelocity,
                              double kinematicViscosity);

struct CouplingIntervalCheck {
  double relaxationTime = 0.0;  // tau_p of the smallest (fastest-relaxing) particle, s
  double couplingInterval = 0.0;  // tau_c = demStepsPerFluidStep * demTimeStep, s
  double ratio = 0.0;           // tau_p / tau_c
  std::string warning;          // empty when the criterion holds
};

/// Checks N DEM steps of dt_DEM per fluid step for particles of (smallest) diameter d and density
/// rho_p at slip velocity `slip`: warns when dt_DEM > tau_p (instability of the explicit drag,
/// seed 000 table 5.4) or tau_p / tau_c < minRatio (accuracy, fig. 5.3 / eq. 5.30).
CouplingIntervalCheck checkCouplingInterval(double demTimeStep, int demStepsPerFluidStep, double particleDensity,
                                            double diameter, double fluidDensity, double viscosity,
                                            double slipVelocity, double minRatio);

}  // namespace gf::coupling
