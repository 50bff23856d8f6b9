// Monitors of a run with several fluids (fluid.vof; docs/vof.md):
//   phase_mass          mass of one phase in the domain (blocked cells left out), its outflow through the open sides (rate
//                       and total), the balance mass + outflow - initial mass (relative), and the
//                       smallest and largest fraction of the phase in a cell
//   interface_position  where a phase's fraction crosses 1/2 for the last time along a grid line
//                       (free-surface height on a vertical line, the front of a dam break on a
//                       horizontal one)
//   fluid_max_velocity  largest |u| of the cell-centred velocity (spurious currents of a fluid at rest)
// Runs without a fluid, or without fluid.vof for the first two, sample NaN.
#include <cmath>
#include <limits>

#include "core/monitor.hpp"
#include "fluid/sampling.hpp"
#include "fluid/solver.hpp"
#include "parallel/reductions.hpp"
#include "vof/vof.hpp"

namespace gf::fluid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A monitor's `phase` key: its name and where it stands in the case file (for the error).
struct PhaseKey {
  std::string name;
  FileLocation where;
  std::string path;
  PhaseKey(Params& p, const std::string& help) : name(p.text({"phase", "-", help}, "")), where(p.location("phase")), path(p.path("phase")) {}
  int index(const Solver& f) const {
    const int i = f.phaseIndex(name);
    if (i < 0) throw CaseError(where, path, "'" + name + "'", "one of the phases of fluid.vof.phases");
    return i;
  }
};

/// The void fraction the fractions hold their contents with (the eps^{n+1} of the last fluid step:
/// in a coupled run the coupler has already moved the coupling fields on by one step when the
/// monitors sample), with blocked cells set to 0. Blocked cells carry no flux, so what the fractions
/// hold there is no fluid of the run; a smoothed void fraction (coupling.smoothing_length) reaches
/// into them and would change a phase's mass there without any flux.
Field openVoidFraction(const Solver& f) {
  Field eps = f.phaseVoidFraction();
  const auto& n = eps.grid().cells;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x)
        if (f.blocked(x, y, z)) eps(x, y, z) = 0.0;
  return eps;
}

class PhaseMassMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit PhaseMassMonitor(Params& p) : phase_(p, "phase_mass, interface_position: name of the phase (fluid.vof.phases)") {}
  std::vector<MonitorColumn> columns() const override {
    return {{"mass", "kg"},          {"outflow_rate", "kg/s"}, {"outflow", "kg"},
            {"balance_error", "-"}, {"fraction_min", "-"},    {"fraction_max", "-"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.fluid || !s.fluid->vofEnabled()) return {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
    const Solver& f = *s.fluid;
    const int i = phase_.index(f);
    const double rho = f.phaseDensity(i);
    const parallel::RankReductionScope ranks(f.decomposition());
    const double mass = rho * vof::phaseVolume(f.phaseFraction(i), openVoidFraction(f));
    const double out = rho * f.phaseOutflowVolume(i);
    if (!started_) {
      initial_ = mass + out;
      started_ = true;
    }
    const double error = initial_ > 0.0 ? (mass + out - initial_) / initial_ : 0.0;
    const auto range = vof::fractionRange(f.phaseFraction(i));
    return {mass, rho * f.phaseOutflowRate(i), out, error, range[0], range[1]};
  }
  void save(BinaryWriter& out) const override {
    out.put(started_);
    out.put(initial_);
  }
  void load(BinaryReader& in) override {
    started_ = in.get<bool>();
    initial_ = in.get<double>();
  }

 private:
  PhaseKey phase_;
  bool started_ = false;
  double initial_ = 0.0;
};

class InterfacePositionMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit InterfacePositionMonitor(Params& p)
      : phase_(p, "phase_mass, interface_position: name of the phase (fluid.vof.phases)") {
    const std::string a = p.choice({"search_axis", "-", "interface_position: direction of the grid line searched upwards"},
                                   {"x", "y", "z"});
    axis_ = a[0] - 'x';
    point_ = p.vec3({"search_point", "m", "interface_position: a point on the line (fixes the two other coordinates)"});
  }
  std::vector<MonitorColumn> columns() const override {
    return {{"position", "m"}, {"distance", "m"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.fluid || !s.fluid->vofEnabled()) return {kNaN, kNaN};
    const Solver& f = *s.fluid;
    const CartesianGrid& G = f.globalGrid();
    const std::vector<double> values = lineValues(f, f.phaseFraction(phase_.index(f)), axis_, point_);
    std::vector<double> position;
    for (int c = 0; c < G.cells[axis_]; ++c) position.push_back(G.origin[axis_] + (c + 0.5) * G.spacing[axis_]);
    const double x = lastCrossing(position, values, 0.5);
    return {x, x - G.origin[axis_]};
  }

 private:
  PhaseKey phase_;
  int axis_ = 2;
  Vec3 point_;
};

class MaxVelocityMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit MaxVelocityMonitor(Params&) {}
  std::vector<MonitorColumn> columns() const override { return {{"max_velocity", "m/s"}}; }
  std::vector<double> sample(const RunState& s) override {
    if (!s.fluid) return {kNaN};
    return {maxCellSpeed(*s.fluid)};
  }
};

}  // namespace
}  // namespace gf::fluid

GF_REGISTER_MODEL(gf::Monitor, gf::fluid::PhaseMassMonitor, "phase_mass",
                  "fluid.vof: mass of a phase, its outflow through the open sides and the mass balance")
GF_REGISTER_MODEL(gf::Monitor, gf::fluid::InterfacePositionMonitor, "interface_position",
                  "fluid.vof: last position where a phase's fraction crosses 1/2 along a grid line")
GF_REGISTER_MODEL(gf::Monitor, gf::fluid::MaxVelocityMonitor, "fluid_max_velocity",
                  "largest |u| of the cell-centred fluid velocity")
