// Mass and number of particles removed by the outlets (deletion regions).
#include "core/monitor.hpp"
#include "dem/system.hpp"
#include "parallel/exchange.hpp"

namespace gf::dem {
namespace {
class RemovedMassMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit RemovedMassMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override { return {{"removed_mass", "kg"}, {"removed_particles", "-"}}; }
  std::vector<double> sample(const RunState& s) override {
    double mass = 0.0, count = 0.0;
    if (s.dem)
      for (const Outlet& o : s.dem->outlets()) {
        mass += o.removedMass;
        count += double(o.removedCount);
      }
    if (s.dem && s.dem->distributed()) {  // (each rank counts what its outlets removed)
      mass = parallel::sumOverRanks(mass);
      count = parallel::sumOverRanks(count);
    }
    return {mass, count};
  }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::RemovedMassMonitor, "removed_mass",
                  "cumulative mass and number of particles removed by all outlets")
