// Monitor 'particle_count': number of particles, their total mass (changes with insertion and
// outlets) and the primary particles they stand for: sum alpha^3 over the particles, alpha the
// coarse-graining factor of each particle's insertion (insertion[].coarse_graining, else
// coupling.coarse_grain_factor; docs/coupling.md sec. 9); equal to the count without coarse graining.
#include <numeric>

#include "core/monitor.hpp"
#include "coupling/coupler.hpp"
#include "dem/system.hpp"

namespace gf {
namespace {

class ParticleCountMonitor final : public Monitor {
 public:
  explicit ParticleCountMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"particles", "-"}, {"particle_mass", "kg"}, {"primary_particles", "-"}};
  }
  std::vector<double> sample(const RunState& state) override {
    const auto& p = monitoredParticles(state);
    // the coupler's factors (insertions and coupling.coarse_grain_factor), else the insertions' own
    std::vector<double> byMaterial = state.dem ? state.dem->coarseGrainingByMaterial() : std::vector<double>{};
    double primaries = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      double alpha = 1.0;
      if (state.coupling)
        alpha = state.coupling->settings().coarseGraining.factorOf(p.type[i]);
      else if (static_cast<std::size_t>(p.type[i]) < byMaterial.size() && byMaterial[p.type[i]] > 0.0)
        alpha = byMaterial[p.type[i]];
      primaries += alpha * alpha * alpha;
    }
    return {static_cast<double>(p.size()), std::accumulate(p.mass.begin(), p.mass.end(), 0.0), primaries};
  }
};

}  // namespace
}  // namespace gf

GF_REGISTER_MODEL(gf::Monitor, gf::ParticleCountMonitor, "particle_count",
                  "number of particles, their total mass and the primary particles they stand for (coarse graining)")
