// Translational and rotational kinetic energy of all particles.
#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {
class KineticEnergyMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit KineticEnergyMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"translational_energy", "J"}, {"rotational_energy", "J"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem) return {0.0, 0.0};
    const EnergyBalance e = s.dem->energy();
    return {e.translational, e.rotational};
  }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::KineticEnergyMonitor, "kinetic_energy",
                  "DEM translational 1/2 m v^2 and rotational 1/2 I w^2 energy")
