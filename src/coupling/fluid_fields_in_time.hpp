#pragma once
// Fluid fields between two fluid steps, as the DEM substeps of coupling.substep_fluid_fields =
// interpolated see them (docs/coupling.md sec. 8). In Simulation::advance the fluid steps first,
// from t_i to t_i+1 = t_i + N dt_dem; the particles then catch up from t_i in N substeps. Before
// substep s (s = 0 .. N-1) the forces are computed from the current particles and the fluid at
// the time the substep's forces act, t_i + (s + 1) dt_dem (velocity Verlet: the force evaluated
// in substep s closes it and opens s + 1):
//   q(theta) = (1 - theta) q(t_i) + theta q(t_i+1),  theta = (s + 1) / N,
// for the cell velocity, the pressure gradient and (if the view has it) div tau. theta = 1 is the
// new view itself, so the last substep and N = 1 see exactly what the held forces see.
// Seed 000 sec. 5.3 (Case II, table 5.2): updating the drag at every DEM step lowers the error of
// the coupling interval by about an order of magnitude against the held Base Case (fig. 5.3).
#include <array>

#include "core/grid.hpp"
#include "coupling/coupler.hpp"

namespace gf::coupling {

class FluidFieldsInTime {
 public:
  /// Copies the fields of `view` (the fluid at t_i, before its step) as the interval's start.
  void keepStart(const FluidView& view) {
    for (int a = 0; a < 3; ++a) {
      copy(view.velocity[a], start_[0][a]);
      copy(view.pressureGradient[a], start_[1][a]);
      copy(view.viscousStressDivergence[a], start_[2][a]);
    }
    hasStart_ = true;
  }

  /// The fluid at fraction theta of the interval: `end` (the fluid at t_i+1) for theta >= 1 or
  /// without a start; otherwise a view of this object's blended fields (valid until the next call)
  /// with end's density, viscosity and the given time step (the virtual mass force's d/dt).
  FluidView at(const FluidView& end, double theta, double timeStep) {
    FluidView view = end;
    view.timeStep = timeStep;
    if (theta >= 1.0 || !hasStart_) return view;
    for (int a = 0; a < 3; ++a) {
      view.velocity[a] = blend(start_[0][a], end.velocity[a], theta, blended_[0][a]);
      view.pressureGradient[a] = blend(start_[1][a], end.pressureGradient[a], theta, blended_[1][a]);
      view.viscousStressDivergence[a] = blend(start_[2][a], end.viscousStressDivergence[a], theta, blended_[2][a]);
    }
    return view;
  }

 private:
  static void copy(const Field* from, Field& to) {
    if (from) to = *from;
    else to = Field();
  }
  /// (1 - theta) start + theta end over every value (ghosts included); nullptr where end has none.
  static const Field* blend(const Field& start, const Field* end, double theta, Field& out) {
    if (!end) return nullptr;
    if (start.data().size() != end->data().size()) return end;  // (no start for this field)
    if (out.data().size() != end->data().size()) out = *end;
    const double* s = start.data().data();
    const double* e = end->data().data();
    double* o = out.data().data();
    const std::size_t n = end->data().size();
    for (std::size_t q = 0; q < n; ++q) o[q] = (1.0 - theta) * s[q] + theta * e[q];
    return &out;
  }

  std::array<std::array<Field, 3>, 3> start_, blended_;  // [velocity, grad p, div tau][axis]
  bool hasStart_ = false;
};

}  // namespace gf::coupling
