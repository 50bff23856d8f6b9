// Angle of repose of a conical heap standing on a horizontal floor (z up) around a vertical axis.
// Height H: top of the highest particle above the floor point `heap_base`. Base radius R: from the
// radial distance r_q from the axis that holds the fraction q of the particles; for a cone of
// radius R the volume inside radius r is 1 - (1 - r/R)^3, so R = r_q / (1 - (1 - q)^(1/3)).
// Angle atan(H / R). Using a quantile rather than the outermost particle keeps the few particles
// that roll away from the heap from setting the base.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {

/// Base radius of a cone whose fraction q of the volume lies within radius rq (see above).
inline double coneRadiusFromQuantile(double rq, double q) { return rq / (1.0 - std::cbrt(1.0 - q)); }

class HeapAngleMonitor final : public Monitor {
 public:
  explicit HeapAngleMonitor(Params& p) {
    base_ = p.vec3({"heap_base", "m", "heap_angle: point of the floor on the heap's vertical axis"}, {});
    quantile_ = p.real({"base_quantile", "-",
                        "heap_angle: fraction q of the particles within r_q; base radius r_q / (1 - (1 - q)^(1/3))",
                        Range{0.0, 1.0, false, false}},
                       0.9);
  }
  std::vector<MonitorColumn> columns() const override {
    return {{"heap_height", "m"}, {"base_radius", "m"}, {"repose_angle", "deg"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem || monitoredParticles(s).size() == 0) return {0, 0, 0};
    const ParticleSet& p = monitoredParticles(s);
    std::vector<double> radial(p.size());
    double top = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 d = p.position[i] - base_;
      radial[i] = std::hypot(d.x, d.y);
      top = std::max(top, d.z + p.radius[i]);
    }
    const std::size_t k = static_cast<std::size_t>(std::llround(quantile_ * double(p.size() - 1)));
    std::nth_element(radial.begin(), radial.begin() + static_cast<std::ptrdiff_t>(k), radial.end());
    const double base = coneRadiusFromQuantile(radial[k], quantile_);
    return {top, base, std::atan2(top, base) * 180.0 / std::numbers::pi};
  }

 private:
  Vec3 base_;
  double quantile_ = 0.9;
};

}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::HeapAngleMonitor, "heap_angle",
                  "angle of repose atan(H / R) of a conical heap on a floor (z up): height H and base radius R from a radial quantile")
