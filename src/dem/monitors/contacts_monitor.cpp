// Contact counts, coordination number and maximum overlap.
#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {
class ContactsMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit ContactsMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"particle_contacts", "-"}, {"wall_contacts", "-"}, {"coordination_number", "-"},
            {"max_overlap_over_radius", "-"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem) return {0, 0, 0, 0};
    const ContactStatistics c = s.dem->contactStatistics();
    return {double(c.particleContacts), double(c.wallContacts), c.coordinationNumber, c.maxOverlapRatio};
  }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::ContactsMonitor, "contacts",
                  "number of particle and wall contacts, coordination number 2 N_c / N, max overlap / radius")
