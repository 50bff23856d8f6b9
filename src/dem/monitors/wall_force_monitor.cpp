// Force and torque of the particles on one wall (torque about the wall's moving centre).
#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {
class WallForceMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit WallForceMonitor(Params& p) : wall_(p.text({"wall", "-", "wall_force: name of the wall"}, "")) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"force_x", "N"}, {"force_y", "N"}, {"force_z", "N"}, {"torque_x", "N m"}, {"torque_y", "N m"},
            {"torque_z", "N m"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem) return std::vector<double>(6, 0.0);
    for (const WallLoad& w : s.dem->wallLoads())
      if (w.name == wall_) return {w.force.x, w.force.y, w.force.z, w.torque.x, w.torque.y, w.torque.z};
    throw Error("monitor wall_force: no wall named '" + wall_ + "'");
  }

 private:
  std::string wall_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::Monitor, gf::dem::WallForceMonitor, "wall_force", "force and torque of the particles on a wall")
