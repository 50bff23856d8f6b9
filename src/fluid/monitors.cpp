// Fluid monitors, registered by name (see core/monitor.hpp):
//   fluid_pressure_drop   mean p(plane 1) - mean p(plane 2)
//   fluid_flow_rate       sum eps u . dA through a plane
//   fluid_kinetic_energy  sum 1/2 rho eps |u|^2 V
//   fluid_max_divergence  max |div(eps u) + d eps/dt| after the last projection
//   fluid_probe           u, v, w, p at a point
// Runs without a fluid sample NaN.
#include <limits>

#include "core/monitor.hpp"
#include "fluid/sampling.hpp"

namespace gf::fluid {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int readAxis(Params& p) {
  const std::string a = p.choice({"plane_normal", "-", "axis normal to the plane(s)"}, {"x", "y", "z"}, "x");
  return a == "x" ? 0 : (a == "y" ? 1 : 2);
}

class PressureDropMonitor : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit PressureDropMonitor(Params& p)
      : axis_(readAxis(p)),
        first_(p.real({"position_1", "m", "coordinate of the upstream plane along axis"})),
        second_(p.real({"position_2", "m", "coordinate of the downstream plane along axis"})) {}
  std::vector<MonitorColumn> columns() const override { return {{"pressure_drop", "Pa"}}; }
  std::vector<double> sample(const RunState& st) override {
    if (!st.fluid) return {kNaN};
    return {planeMeanPressure(*st.fluid, axis_, first_) - planeMeanPressure(*st.fluid, axis_, second_)};
  }

 private:
  int axis_;
  double first_, second_;
};

class FlowRateMonitor : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit FlowRateMonitor(Params& p)
      : axis_(readAxis(p)), position_(p.real({"position", "m", "coordinate of the plane along axis"})) {}
  std::vector<MonitorColumn> columns() const override { return {{"flow_rate", "m^3/s"}}; }
  std::vector<double> sample(const RunState& st) override {
    if (!st.fluid) return {kNaN};
    return {flowRate(*st.fluid, axis_, position_)};
  }

 private:
  int axis_;
  double position_;
};

class KineticEnergyMonitor : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit KineticEnergyMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override { return {{"fluid_kinetic_energy", "J"}}; }
  std::vector<double> sample(const RunState& st) override {
    if (!st.fluid) return {kNaN};
    return {kineticEnergy(*st.fluid)};
  }
};

class MaxDivergenceMonitor : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit MaxDivergenceMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"max_divergence", "1/s"}, {"pressure_iterations", "-"}, {"pressure_residual", "-"}};
  }
  std::vector<double> sample(const RunState& st) override {
    if (!st.fluid) return {kNaN, kNaN, kNaN};
    const auto& s = st.fluid->lastStep();
    return {st.fluid->maxDivergence(), static_cast<double>(s.pressureIterations), s.pressureResidual};
  }
};

class ProbeMonitor : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit ProbeMonitor(Params& p) : point_(p.vec3({"probe_point", "m", "probe location"})) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"velocity_x", "m/s"}, {"velocity_y", "m/s"}, {"velocity_z", "m/s"}, {"pressure", "Pa"}};
  }
  std::vector<double> sample(const RunState& st) override {
    if (!st.fluid) return {kNaN, kNaN, kNaN, kNaN};
    const auto v = probe(*st.fluid, point_);
    return {v[0], v[1], v[2], v[3]};
  }

 private:
  Vec3 point_;
};

}  // namespace

GF_REGISTER_MODEL(gf::Monitor, PressureDropMonitor, "fluid_pressure_drop",
                  "mean pressure difference between two planes normal to an axis")
GF_REGISTER_MODEL(gf::Monitor, FlowRateMonitor, "fluid_flow_rate", "flow rate sum(eps u . dA) through a plane")
GF_REGISTER_MODEL(gf::Monitor, KineticEnergyMonitor, "fluid_kinetic_energy", "fluid kinetic energy")
GF_REGISTER_MODEL(gf::Monitor, MaxDivergenceMonitor, "fluid_max_divergence",
                  "max |div(eps u) + d eps/dt| and pressure-solver statistics of the last step")
GF_REGISTER_MODEL(gf::Monitor, ProbeMonitor, "fluid_probe", "fluid velocity and pressure at a point")

}  // namespace gf::fluid
