// The Coupler driving the real fluid solver (src/fluid): a fixed bed of particles (one per cell,
// uniform eps) in a channel with a given superficial velocity. With model A and the semi-implicit
// exchange, the steady pressure gradient inside the bed must equal the drag law's packed-bed
// value eps dp/dx = -n F_d (settling.hpp; for gidaspow this is Ergun). Checks that the API fits
// the solver's contract (grid, coupling fields, cell velocity, pressure gradient) end to end.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/domain.hpp"
#include "coupling/settling.hpp"
#include "coupling_test_helpers.hpp"
#include "fluid/solver.hpp"

using namespace gf;
using namespace gf::coupling;

namespace {

double bedPressureGradient(const std::string& law, const std::string& exchange, double dt, int steps,
                           double* expected, double* edgeVelocity = nullptr, double* bulkVelocity = nullptr,
                           const std::string& extra = "") {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [1, 0.05, 0.05], periodic: [0, 1, 0]}
fluid:
  model: A
  density: 1.0
  viscosity: 0.01
  cells: [40, 2, 1]
  pressure: {tolerance: 1e-12}
  boundaries:
    x_min: {type: inlet, velocity: [0.1, 0, 0]}
    x_max: {type: pressure_outlet, pressure: 0}
coupling:
  void_fraction: pcm
  interpolation: cell
  min_void_fraction: 0
  drag_law: )" + law + "\n  exchange: " + exchange + "\n" + extra;
  Params params = Params::loadString(yaml, "bed.yaml");
  const Domain domain = Domain::read(params);
  fluid::Solver fluid(params, domain, Vec3{});
  Coupler coupler(params, fluid.grid(), domain.periodic, Vec3{}, ExchangeModel::A);
  params.checkUnknownKeys();
  const CartesianGrid& g = fluid.grid();
  // one particle per cell for 10 <= i < 30: eps = 1 - V_p / V_c = 0.6
  const double vp = 0.4 * g.cellVolume();
  const double r = std::cbrt(3.0 * vp / (4.0 * std::numbers::pi));
  dem::ParticleSet bed;
  for (int j = 0; j < 2; ++j)
    for (int i = 10; i < 30; ++i) bed.add(j * 100 + i, 0, r, 2500.0, g.cellCentre(i, j, 0));
  CouplingFields& fields = fluid.couplingFields();
  coupler.computeVoidFraction(bed, fields);
  coupler.computeVoidFraction(bed, fields);  // eps_old = eps: a bed at rest
  Field u[3], gradP[3];
  for (int n = 0; n < steps; ++n) {
    fluid.cellVelocity(u);
    fluid.pressureGradient(gradP);
    FluidView view;
    for (int a = 0; a < 3; ++a) {
      view.velocity[a] = &u[a];
      view.pressureGradient[a] = &gradP[a];
    }
    view.density = fluid.density();
    view.viscosity = fluid.viscosity();
    view.timeStep = dt;
    coupler.computeParticleForces(view, fields, bed);
    for (auto& v : bed.velocity) v = {};  // fixed bed
    coupler.fillFluidSources(bed, fields);
    EXPECT_LE(norm(coupler.momentumBalanceError()), 1e-12 * coupler.exchangedForceScale());
    fluid.step(dt);
  }
  *expected = -packedBedPressureGradient(coupler.dragLaw(), {1.0, 0.01}, 2.0 * r, 0.6, 0.1);
  // fluid velocity at the particle of the first bed cell (i = 10, after the free inlet region) and
  // at one in the middle of the bed (i = 20), j = 0: the slip, the bed being at rest
  if (edgeVelocity) *edgeVelocity = coupler.slipVelocities()[0].x;
  if (bulkVelocity) *bulkVelocity = coupler.slipVelocities()[10].x;
  const double dx = (25 - 15) * g.spacing.x;
  return (fluid.pressure()(25, 0, 0) - fluid.pressure()(15, 0, 0)) / dx;
}

}  // namespace

TEST(FluidIntegration, FixedBedPressureGradientMatchesTheDragLaw) {
  // K dt / rho = 490 * 0.01 / 1: the explicit drag needs a smaller step (K dt / (rho eps) < 2)
  for (const char* law : {"gidaspow", "beetstra"}) {
    double expected = 0.0;
    const double implicitGradient = bedPressureGradient(law, "implicit", 0.01, 100, &expected);
    EXPECT_LT(expected, -50.0);  // n beta U / eps^2 ~ 130 Pa/m
    EXPECT_NEAR(implicitGradient / expected, 1.0, 1e-3) << law << " " << implicitGradient << " " << expected;
    const double explicitGradient = bedPressureGradient(law, "explicit", 0.001, 100, &expected);
    EXPECT_NEAR(explicitGradient / expected, 1.0, 1e-3) << law << " " << explicitGradient;
  }
}

TEST(FluidIntegration, ParticlesInTheFirstBedCellSeeTheInterstitialVelocityOfTheirCell) {
  // Free channel (eps = 1), then the fixed bed at eps = 0.6, superficial velocity U = 0.1 m/s:
  // every bed particle must see u = U / eps = 0.1667 m/s, the first bed cell's included
  // (velocity_reconstruction: flux). The fluid's face-mean cell velocity gives (U/0.8 + U/0.6)/2
  // there, 12.5 % low (face_mean, the default). The momentum balance holds in both (checked
  // every step in bedPressureGradient).
  double expected = 0.0, edge = 0.0, bulk = 0.0;
  bedPressureGradient("gidaspow", "implicit", 0.01, 100, &expected, &edge, &bulk,
                      "  velocity_reconstruction: flux\n");
  EXPECT_NEAR(bulk, 0.1 / 0.6, 1e-3 * 0.1 / 0.6);
  EXPECT_NEAR(edge / bulk, 1.0, 1e-3);
  bedPressureGradient("gidaspow", "implicit", 0.01, 100, &expected, &edge, &bulk,
                      "  velocity_reconstruction: face_mean\n");
  EXPECT_NEAR(edge / bulk, 0.875, 1e-3);
}
