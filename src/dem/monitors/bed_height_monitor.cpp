// Height of the particle bed along `up`: top of the highest particle and mean centre height.
#include <algorithm>
#include <limits>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {
class BedHeightMonitor final : public Monitor {
 public:
  explicit BedHeightMonitor(Params& p) {
    up_ = normalized(p.vec3({"up", "-", "bed_height: upward direction"}, {0, 0, 1}));
    base_ = p.vec3({"base", "m", "bed_height: heights are measured from this point"}, {});
  }
  std::vector<MonitorColumn> columns() const override { return {{"bed_height", "m"}, {"mean_centre_height", "m"}}; }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem || monitoredParticles(s).size() == 0) return {0, 0};
    const ParticleSet& p = monitoredParticles(s);
    double top = -std::numeric_limits<double>::infinity(), sum = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double h = dot(p.position[i] - base_, up_);
      top = std::max(top, h + p.radius[i]);
      sum += h;
    }
    return {top, sum / double(p.size())};
  }

 private:
  Vec3 up_, base_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::BedHeightMonitor, "bed_height",
                  "height of the highest particle top and mean centre height along 'up'")
