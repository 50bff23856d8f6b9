#include "coupling/coupling_interval.hpp"

#include <cmath>

#include <fmt/format.h>

namespace gf::coupling {

double particleRelaxationTime(double rhoP, double d, double mu, double re) {
  return rhoP * d * d / (18.0 * mu) / (1.0 + 0.15 * std::pow(re, 0.687));
}

double scaledCouplingInterval(double tauC1, double d1, double d2, double slip, double nu) {
  const double re1 = slip * d1 / nu;
  const double re2 = slip * d2 / nu;  // eq. 5.30: the slip of the original particle is kept
  return (d2 / d1) * (d2 / d1) * (1.0 + 0.15 * std::pow(re1, 0.687)) / (1.0 + 0.15 * std::pow(re2, 0.687)) * tauC1;
}

CouplingIntervalCheck checkCouplingInterval(double dtDem, int steps, double rhoP, double d, double rhoF, double mu,
                                            double slip, double minRatio) {
  CouplingIntervalCheck c;
  c.relaxationTime = particleRelaxationTime(rhoP, d, mu, rhoF * slip * d / mu);
  c.couplingInterval = steps * dtDem;
  c.ratio = c.relaxationTime / c.couplingInterval;
  if (dtDem > c.relaxationTime) {
    c.warning = fmt::format(
        "DEM time step {:.3g} s exceeds the particle relaxation time {:.3g} s (d = {:.3g} m, seed 000 eq. 5.22): "
        "the explicit drag update is unstable; reduce the DEM step",
        dtDem, c.relaxationTime, d);
  } else if (c.ratio < minRatio) {
    c.warning = fmt::format(
        "coupling interval {} x {:.3g} s = {:.3g} s is too long for particles of d = {:.3g} m: relaxation time "
        "{:.3g} s gives tau_p/tau_c = {:.3g} < {:.3g} (seed 000 eq. 5.30); use at most {} DEM steps per fluid step",
        steps, dtDem, c.couplingInterval, d, c.relaxationTime, c.ratio, minRatio,
        std::max(1, static_cast<int>(std::floor(c.relaxationTime / (minRatio * dtDem)))));
  }
  return c;
}

}  // namespace gf::coupling
