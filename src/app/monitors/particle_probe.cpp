// Monitor 'particle_probe': position, velocity, angular velocity and total force of the particle
// with a given id (e.g. a single sphere in a bounce or free-fall validation).
#include <cmath>
#include <limits>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf {
namespace {

class ParticleProbeMonitor final : public Monitor {
 public:
  explicit ParticleProbeMonitor(Params& p)
      : id_(p.integer({"id", "-", "id of the probed particle (ids count from 0 in insertion order)", Range::nonNegative()},
                      0)) {}

  std::vector<MonitorColumn> columns() const override {
    return {{"x", "m"},      {"y", "m"},      {"z", "m"},      {"vx", "m/s"},  {"vy", "m/s"},
            {"vz", "m/s"},   {"wx", "rad/s"}, {"wy", "rad/s"}, {"wz", "rad/s"}, {"fx", "N"},
            {"fy", "N"},     {"fz", "N"}};
  }

  std::vector<double> sample(const RunState& state) override {
    const auto& p = monitoredParticles(state);
    if (index_ >= p.size() || p.id[index_] != id_) {  // find it again after insertion/removal/reordering
      index_ = p.size();
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.id[i] == id_) index_ = i;
    }
    if (index_ >= p.size()) return std::vector<double>(columns().size(), std::numeric_limits<double>::quiet_NaN());
    const std::size_t i = index_;
    const Vec3 x = p.position[i], v = p.velocity[i], w = p.angularVelocity[i], f = p.force[i];
    return {x.x, x.y, x.z, v.x, v.y, v.z, w.x, w.y, w.z, f.x, f.y, f.z};
  }

 private:
  std::int64_t id_;
  std::size_t index_ = 0;
};

}  // namespace
}  // namespace gf

GF_REGISTER_MODEL(gf::Monitor, gf::ParticleProbeMonitor, "particle_probe",
                  "position, velocity, angular velocity and total force (incl. gravity) of one particle, by id; NaN "
                  "while it does not exist")
