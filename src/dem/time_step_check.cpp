#include "dem/time_step_check.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace gf::dem {

double rayleighTime(double radius, double density, double youngsModulus, double poissonRatio) {
  const double shearModulus = youngsModulus / (2.0 * (1.0 + poissonRatio));
  return std::numbers::pi * radius * std::sqrt(density / shearModulus) / (0.1631 * poissonRatio + 0.8766);
}

TimeStepStatus checkTimeStep(double dt, double tRayleigh) {
  TimeStepStatus s;
  s.ratio = dt / tRayleigh;
  if (s.ratio > 0.5) {
    s.verdict = TimeStepVerdict::Error;
    s.message = fmt::format("DEM time step {:g} s is {:.0f} % of the Rayleigh time {:g} s (limit 50 %); use dt <= {:g} s",
                            dt, 100.0 * s.ratio, tRayleigh, 0.2 * tRayleigh);
  } else if (s.ratio > 0.2) {
    s.verdict = TimeStepVerdict::Warning;
    s.message = fmt::format("DEM time step {:g} s is {:.0f} % of the Rayleigh time {:g} s (recommended <= 20 %)", dt,
                            100.0 * s.ratio, tRayleigh);
  }
  return s;
}

}  // namespace gf::dem
