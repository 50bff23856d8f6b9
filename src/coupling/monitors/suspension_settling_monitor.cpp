// Monitor "suspension_settling": mean velocities of a homogeneous suspension along `settling_axis`:
//   particle_velocity      mean particle velocity v_p (number mean; monodisperse: volume mean), m/s
//   fluid_flux             mean superficial fluid velocity q_f = <eps u> over the cells, m/s
//   solid_fraction         phi = particle volume / domain volume
//   hindered_settling_velocity  -(v_p - j), the particle velocity relative to the zero-volume-flux
//                          frame j = q_f + phi v_p (the frame of batch sedimentation, in which
//                          Richardson & Zaki 1954 measured v = v_t eps^n), positive downwards
//                          when the axis points up.
#include <algorithm>
#include <numbers>

#include "core/monitor.hpp"
#include "dem/system.hpp"
#include "fluid/solver.hpp"
#include "parallel/exchange.hpp"

namespace gf::coupling {
namespace {

class SuspensionSettlingMonitor final : public Monitor {
 public:
  explicit SuspensionSettlingMonitor(Params& p) {
    const std::string a = p.choice(
        {"settling_axis", "-", "suspension_settling: axis of the velocities (pointing against gravity)"}, {"x", "y", "z"},
        "z");
    axis_ = a[0] - 'x';
  }
  std::vector<MonitorColumn> columns() const override {
    return {{"particle_velocity", "m/s"}, {"fluid_flux", "m/s"}, {"solid_fraction", "-"},
            {"hindered_settling_velocity", "m/s"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem || !s.fluid) return {0.0, 0.0, 0.0, 0.0};
    const double flux = meanSuperficialVelocity(*s.fluid);  // (collective under MPI)
    // (under MPI rank 0 holds every particle and writes the file; the others return zeros)
    const dem::ParticleSet& p = monitoredParticles(s);
    if (p.size() == 0) return {0.0, 0.0, 0.0, 0.0};
    double vsum = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      vsum += p.velocity[i][axis_];
      volume += std::numbers::pi / 6.0 * 8.0 * p.radius[i] * p.radius[i] * p.radius[i];
    }
    const double vp = vsum / double(p.size());
    const CartesianGrid& g = s.fluid->globalGrid();
    const double phi = volume / (g.cellVolume() * g.cells[0] * g.cells[1] * g.cells[2]);
    const double frame = flux + phi * vp;
    return {vp, flux, phi, -(vp - frame)};
  }

 private:
  /// <eps u> along the axis over every cell of the grid (all ranks').
  double meanSuperficialVelocity(const fluid::Solver& f) const {
    const CartesianGrid& g = f.grid();
    const Field& u = f.velocity(axis_);
    const Field& eps = f.couplingFields().voidFraction;
    double flux = 0.0;
    const int da = axis_ == 0, db = axis_ == 1, dc = axis_ == 2;
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i)
          flux += eps(i, j, k) * 0.5 * (u(i, j, k) + u(i + da, j + db, k + dc));
    if (f.decomposition().distributed()) flux = parallel::sumOverRanks(flux);
    const CartesianGrid& whole = f.globalGrid();
    return flux / (double(whole.cells[0]) * whole.cells[1] * whole.cells[2]);
  }

  int axis_ = 2;
};

}  // namespace
}  // namespace gf::coupling

GF_REGISTER_MODEL(gf::Monitor, gf::coupling::SuspensionSettlingMonitor, "suspension_settling",
                  "mean particle and superficial fluid velocities of a suspension; hindered settling velocity")
