// Mass crossing a plane: cumulative net mass in the direction of the normal and the mean rate
// since the previous sample. Tracks which side each particle (by id) was on at the last sample;
// sample often enough that no particle crosses twice between samples. The per-particle sides,
// the running total and the last sample time are checkpointed, so a restarted run writes the
// same numbers as an uninterrupted one.
#include <algorithm>
#include <unordered_map>
#include <utility>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {
class MassFlowMonitor final : public Monitor {
 public:
  explicit MassFlowMonitor(Params& p) {
    point_ = p.vec3({"point", "m", "mass_flow: a point on the counting plane"}, {});
    normal_ = normalized(p.vec3({"normal", "-", "mass_flow: positive flow direction"}, {0, 0, -1}));
  }
  std::vector<MonitorColumn> columns() const override { return {{"mass_crossed", "kg"}, {"mass_flow_rate", "kg/s"}}; }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem) return {0, 0};
    const ParticleSet& p = monitoredParticles(s);
    double crossed = 0.0;
    std::unordered_map<std::int64_t, bool> side;
    side.reserve(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      const bool beyond = dot(p.position[i] - point_, normal_) > 0.0;
      side[p.id[i]] = beyond;
      auto it = previous_.find(p.id[i]);
      if (it != previous_.end() && it->second != beyond) crossed += beyond ? p.mass[i] : -p.mass[i];
    }
    previous_.swap(side);
    total_ += crossed;
    const double rate = s.time > lastTime_ ? crossed / (s.time - lastTime_) : 0.0;
    lastTime_ = s.time;
    return {total_, rate};
  }
  void save(BinaryWriter& out) const override {
    out.put(total_);
    out.put(lastTime_);
    // Sorted by id: the checkpoint does not depend on the hash map's iteration order.
    std::vector<std::int64_t> ids;
    std::vector<std::uint8_t> beyond;
    ids.reserve(previous_.size());
    for (const auto& entry : previous_) ids.push_back(entry.first);
    std::sort(ids.begin(), ids.end());
    beyond.reserve(ids.size());
    for (std::int64_t id : ids) beyond.push_back(previous_.at(id) ? 1 : 0);
    out.putVector(ids);
    out.putVector(beyond);
  }
  void load(BinaryReader& in) override {
    total_ = in.get<double>();
    lastTime_ = in.get<double>();
    const std::vector<std::int64_t> ids = in.getVector<std::int64_t>();
    const std::vector<std::uint8_t> beyond = in.getVector<std::uint8_t>();
    if (ids.size() != beyond.size())
      throw CheckpointError("checkpoint is corrupt: mass_flow monitor arrays do not match");
    previous_.clear();
    previous_.reserve(ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) previous_[ids[k]] = beyond[k] != 0;
  }

 private:
  Vec3 point_, normal_;
  std::unordered_map<std::int64_t, bool> previous_;
  double total_ = 0.0, lastTime_ = 0.0;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::MassFlowMonitor, "mass_flow",
                  "mass of particles crossing a plane (cumulative, and rate since the last sample)")
