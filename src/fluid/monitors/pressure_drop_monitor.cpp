// Monitor "pressure_drop": mean fluid pressure of the cell layer containing `lower` minus that of
// the layer containing `upper` (positions along `flow_axis`), the distance between the two layer
// centres, and the mean superficial velocity eps u through the face at the bottom of the `lower`
// layer. The pressure includes the hydrostatic part (the fluid carries eps rho g), so for a bed
// at rest  pressure_drop = rho_f g distance + (buoyant bed weight) / area.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/monitor.hpp"
#include "fluid/sampling.hpp"
#include "fluid/solver.hpp"

namespace gf::fluid {
namespace {

class PressureDropMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit PressureDropMonitor(Params& p) {
    const std::string a = p.choice({"flow_axis", "-", "pressure_drop: axis along which the pressure drop is taken"},
                                   {"x", "y", "z"}, "z");
    axis_ = a[0] - 'x';
    lower_ = p.real({"lower", "m", "pressure_drop: position (along flow_axis) in the upstream cell layer"}, 0.0);
    upper_ = p.real({"upper", "m", "pressure_drop: position (along flow_axis) in the downstream cell layer"}, 0.0);
  }
  std::vector<MonitorColumn> columns() const override {
    return {{"pressure_drop", "Pa"}, {"distance", "m"}, {"superficial_velocity", "m/s"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.fluid) return {0.0, 0.0, 0.0};
    const Solver& f = *s.fluid;
    const CartesianGrid& g = f.globalGrid();  // (layers of the whole grid; sums across the ranks)
    const int lo = layer(g, lower_), hi = layer(g, upper_);
    const double distance = (hi - lo) * g.spacing[axis_];
    return {meanPressure(f, lo) - meanPressure(f, hi), distance, superficialVelocity(f, lo)};
  }

 private:
  int layer(const CartesianGrid& g, double x) const {
    const int n = g.cells[axis_];
    return std::clamp(int(std::floor((x - g.origin[axis_]) / g.spacing[axis_])), 0, n - 1);
  }
  /// Calls body(i, j, k) for every cell of this rank's box in layer `l` (of the whole grid)
  /// normal to the axis (local indices).
  template <class Body>
  void forLayer(const Solver& f, int l, Body&& body) const {
    if (!ownsCellAlong(f, axis_, l)) return;
    const CartesianGrid& g = f.grid();
    l = localIndex(f, axis_, l);
    const int b1 = (axis_ + 1) % 3, b2 = (axis_ + 2) % 3;
    for (int q = 0; q < g.cells[b2]; ++q)
      for (int r = 0; r < g.cells[b1]; ++r) {
        int idx[3];
        idx[axis_] = l;
        idx[b1] = r;
        idx[b2] = q;
        body(idx[0], idx[1], idx[2]);
      }
  }
  double meanPressure(const Solver& f, int l) const {
    double sum = 0.0, n = 0.0;
    forLayer(f, l, [&](int i, int j, int k) {
      if (f.blocked(i, j, k)) return;
      sum += f.pressure()(i, j, k);
      n += 1.0;
    });
    std::tie(sum, n) = sumOverRanks(f, std::pair<double, double>{sum, n});
    return n > 0 ? sum / n : 0.0;
  }
  /// Mean of eps_face u over the face below layer l (eps_face: mean of the two adjacent cells).
  double superficialVelocity(const Solver& f, int l) const {
    const Field& u = f.velocity(axis_);
    const Field& eps = f.couplingFields().voidFraction;
    double sum = 0.0, n = 0.0;
    forLayer(f, l, [&](int i, int j, int k) {
      const int im = i - (axis_ == 0), jm = j - (axis_ == 1), km = k - (axis_ == 2);
      sum += 0.5 * (eps(i, j, k) + eps(im, jm, km)) * u(i, j, k);
      n += 1.0;
    });
    std::tie(sum, n) = sumOverRanks(f, std::pair<double, double>{sum, n});
    return n > 0 ? sum / n : 0.0;
  }

  int axis_ = 2;
  double lower_ = 0.0, upper_ = 0.0;
};

}  // namespace
}  // namespace gf::fluid

GF_REGISTER_MODEL(gf::Monitor, gf::fluid::PressureDropMonitor, "pressure_drop",
                  "mean fluid pressure difference between two cell layers, and the superficial velocity")
