// Monitor "coupling_balance": Newton's third law and volume conservation of the coupling, sampled
// every time the monitor runs (the lead samples it every coupling step):
//   momentum_error_{x,y,z}  sum of exchanged particle forces + sum of fluid sources x V_c, N
//   relative_momentum_error |error| / sum |exchanged force|, -
//   particle_volume, deposited_volume, clipped_volume  (m^3; clipped = lost to min_void_fraction)
#include <cmath>

#include "core/monitor.hpp"
#include "coupling/coupler.hpp"

namespace gf::coupling {
namespace {

class CouplingBalanceMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit CouplingBalanceMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"momentum_error_x", "N"},  {"momentum_error_y", "N"}, {"momentum_error_z", "N"},
            {"relative_momentum_error", "-"}, {"particle_volume", "m^3"}, {"deposited_volume", "m^3"},
            {"clipped_volume", "m^3"}};
  }
  std::vector<double> sample(const RunState& state) override {
    if (!state.coupling) return std::vector<double>(7, 0.0);
    const Coupler& c = *state.coupling;
    const Vec3 e = c.momentumBalanceError();
    const double scale = c.exchangedForceScale();
    return {e.x, e.y, e.z, scale > 0.0 ? norm(e) / scale : 0.0, c.particleVolume(), c.depositedVolume(),
            c.clippedVolume()};
  }
};

}  // namespace
GF_REGISTER_MODEL(Monitor, CouplingBalanceMonitor, "coupling_balance",
                  "Newton's third law of the fluid-particle exchange and particle-volume conservation")
}  // namespace gf::coupling
