// Monitor 'particle_statistics': min/max/mean centre coordinate along an axis, top of the
// highest particle, translational kinetic energy and speeds of all particles.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf {
namespace {

class ParticleStatisticsMonitor final : public Monitor {
 public:
  explicit ParticleStatisticsMonitor(Params& p) {
    const std::string axis = p.choice({"axis", "-", "coordinate the position statistics are taken along"},
                                      {"x", "y", "z"}, "z");
    axisName_ = axis;
    axis_ = axis == "x" ? 0 : axis == "y" ? 1 : 2;
  }

  std::vector<MonitorColumn> columns() const override {
    return {{"particles", "-"},
            {axisName_ + "_min", "m"},
            {axisName_ + "_max", "m"},
            {axisName_ + "_mean", "m"},
            {axisName_ + "_top", "m"},
            {"translational_energy", "J"},
            {"speed_mean", "m/s"},
            {"speed_max", "m/s"}};
  }

  std::vector<double> sample(const RunState& state) override {
    const auto& p = monitoredParticles(state);
    const std::size_t n = p.size();
    if (n == 0) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return {0.0, nan, nan, nan, nan, 0.0, nan, nan};
    }
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, top = -lo, sum = 0.0;
    double energy = 0.0, speedSum = 0.0, speedMax = 0.0;
    for (std::size_t i = 0; i < n; ++i) {  // sequential: deterministic sums
      const double c = p.position[i][axis_];
      lo = std::min(lo, c);
      hi = std::max(hi, c);
      top = std::max(top, c + p.radius[i]);
      sum += c;
      const double v2 = normSquared(p.velocity[i]);
      energy += 0.5 * p.mass[i] * v2;  // E = 1/2 m v^2
      const double speed = std::sqrt(v2);
      speedSum += speed;
      speedMax = std::max(speedMax, speed);
    }
    const double count = static_cast<double>(n);
    return {count, lo, hi, sum / count, top, energy, speedSum / count, speedMax};
  }

 private:
  std::string axisName_;
  int axis_ = 2;
};

}  // namespace
}  // namespace gf

GF_REGISTER_MODEL(gf::Monitor, gf::ParticleStatisticsMonitor, "particle_statistics",
                  "number of particles, min/max/mean centre coordinate and top surface along an axis, translational "
                  "kinetic energy, mean and max speed")
