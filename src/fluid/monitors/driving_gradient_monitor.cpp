// Monitor "fluid_driving_gradient": the mean driving pressure gradient -dp/dx along the driving
// axis (imposed, or found by the flow-rate controller), Pa/m. With an imposed bulk velocity U in
// a plane channel of height H it tends to 12 mu U / H^2 (White, Viscous Fluid Flow, eq. 3-42).
// Runs without a fluid sample NaN.
#include <limits>

#include "core/monitor.hpp"
#include "fluid/solver.hpp"

namespace gf::fluid {
namespace {

class DrivingGradientMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit DrivingGradientMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override { return {{"driving_gradient", "Pa/m"}}; }
  std::vector<double> sample(const RunState& s) override {
    if (!s.fluid) return {std::numeric_limits<double>::quiet_NaN()};
    return {s.fluid->drivingPressureGradient()};
  }
};

}  // namespace
}  // namespace gf::fluid

GF_REGISTER_MODEL(gf::Monitor, gf::fluid::DrivingGradientMonitor, "fluid_driving_gradient",
                  "mean driving pressure gradient -dp/dx along the driving axis (imposed or flow-rate controlled)")
