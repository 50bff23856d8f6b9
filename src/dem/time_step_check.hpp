#pragma once
// Time-step check against the Rayleigh time of the smallest/softest particle:
// t_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) (Li, Xu & Thornton 2005, Powder Technol. 160:219).
// dt above 20 % of t_R is a warning, above 50 % an error.
#include <string>

namespace gf::dem {

enum class TimeStepVerdict { Ok, Warning, Error };

struct TimeStepStatus {
  TimeStepVerdict verdict = TimeStepVerdict::Ok;
  double ratio = 0.0;   // dt / t_R
  std::string message;  // empty when Ok
};

double rayleighTime(double radius, double density, double youngsModulus, double poissonRatio);
TimeStepStatus checkTimeStep(double dt, double rayleighTime);

}  // namespace gf::dem
