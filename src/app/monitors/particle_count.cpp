// Monitor 'particle_count': number of particles and their total mass (changes with insertion and outlets).
#include <numeric>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf {
namespace {

class ParticleCountMonitor final : public Monitor {
 public:
  explicit ParticleCountMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override { return {{"particles", "-"}, {"particle_mass", "kg"}}; }
  std::vector<double> sample(const RunState& state) override {
    const auto& p = monitoredParticles(state);
    return {static_cast<double>(p.size()), std::accumulate(p.mass.begin(), p.mass.end(), 0.0)};
  }
};

}  // namespace
}  // namespace gf

GF_REGISTER_MODEL(gf::Monitor, gf::ParticleCountMonitor, "particle_count", "number of particles and their total mass")
