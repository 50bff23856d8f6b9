// Monitor "fluid_scalar_probe": the passive scalar of the cell containing probe_point, and the
// smallest and largest scalar over all open cells (boundedness of the TVD advection).
// Runs without a fluid, or without the scalar, sample NaN.
#include <algorithm>
#include <limits>

#include "core/monitor.hpp"
#include "fluid/sampling.hpp"
#include "fluid/solver.hpp"

namespace gf::fluid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class ScalarProbeMonitor final : public Monitor {
 public:
  bool readsParticles() const override { return false; }  // (fields and reduced sums only)
  explicit ScalarProbeMonitor(Params& p)
      : point_(p.vec3({"probe_point", "m", "fluid_scalar_probe: point whose cell's scalar is reported"})) {}
  std::vector<MonitorColumn> columns() const override {
    return {{"scalar", "-"}, {"scalar_min", "-"}, {"scalar_max", "-"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.fluid || !s.fluid->hasScalar()) return {kNaN, kNaN, kNaN};
    const Solver& f = *s.fluid;
    const CartesianGrid& g = f.grid();
    const Field& c = f.scalar();
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i) {
          if (f.blocked(i, j, k)) continue;
          lo = std::min(lo, c(i, j, k));
          hi = std::max(hi, c(i, j, k));
        }
    // (the point's cell of the whole grid, from the rank that holds it; extrema across the ranks)
    const CartesianGrid& G = f.globalGrid();
    const auto cell = G.cellOf(point_);
    const int i = std::clamp(cell[0], 0, G.cells[0] - 1), j = std::clamp(cell[1], 0, G.cells[1] - 1),
              k = std::clamp(cell[2], 0, G.cells[2] - 1);
    if (!f.decomposition().distributed()) return {c(i, j, k), lo, hi};
    const bool mine = ownsCellAlong(f, 0, i) && ownsCellAlong(f, 1, j) && ownsCellAlong(f, 2, k);
    const double value = mine ? c(localIndex(f, 0, i), localIndex(f, 1, j), localIndex(f, 2, k)) : 0.0;
    return {sumOverRanks(f, value), minOverRanks(f, lo), maxOverRanks(f, hi)};
  }

 private:
  Vec3 point_;
};

}  // namespace
}  // namespace gf::fluid

GF_REGISTER_MODEL(gf::Monitor, gf::fluid::ScalarProbeMonitor, "fluid_scalar_probe",
                  "passive scalar at a point (its cell) and its min/max over the open cells")
