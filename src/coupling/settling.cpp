#include "coupling/settling.hpp"

#include <cmath>
#include <functional>
#include <numbers>

namespace gf::coupling {
namespace {

/// Root of a increasing function on [0, hi], hi grown until bracketed.
double solveIncreasing(const std::function<double(double)>& residual, double hi) {
  while (residual(hi) < 0.0) hi *= 2.0;
  double lo = 0.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double terminalVelocity(const DragLaw& law, const SettlingFluid& f, double d, double rhoP, double g, double eps) {
  const double load = (rhoP - f.density) * std::numbers::pi / 6.0 * d * d * d * g;
  auto residual = [&](double v) {
    const double re = f.density * v * d / f.viscosity;
    return particleDragCoefficient(f.viscosity, d, law.correction(re, eps)) * v - load;
  };
  return solveIncreasing(residual, load / (3.0 * std::numbers::pi * f.viscosity * d));
}

double hinderedSettlingVelocity(const DragLaw& law, const SettlingFluid& f, double d, double rhoP, double g,
                                double eps) {
  const double volume = std::numbers::pi / 6.0 * d * d * d;
  const double load = eps * (rhoP - f.density) * volume * g;
  auto residual = [&](double slip) {
    const double re = f.density * slip * d / f.viscosity;
    return particleDragCoefficient(f.viscosity, d, law.correction(re, eps)) * slip - load;
  };
  const double stokes = load / (3.0 * std::numbers::pi * f.viscosity * d);
  const double slip = solveIncreasing(residual, stokes);
  return eps * slip;
}

double packedBedPressureGradient(const DragLaw& law, const SettlingFluid& f, double d, double eps, double u) {
  const double slip = u / eps;
  const double re = f.density * slip * d / f.viscosity;
  const double beta = particleDragCoefficient(f.viscosity, d, law.correction(re, eps));
  const double volume = std::numbers::pi / 6.0 * d * d * d;
  return (1.0 - eps) / volume * beta * slip / eps;
}

double ergunPressureGradient(const SettlingFluid& f, double d, double eps, double u) {
  const double phi = 1.0 - eps;
  const double e3 = eps * eps * eps;
  return 150.0 * f.viscosity * phi * phi * u / (e3 * d * d) + 1.75 * f.density * phi * u * u / (e3 * d);
}

}  // namespace gf::coupling
