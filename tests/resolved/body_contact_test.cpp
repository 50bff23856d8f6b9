// Contacts of resolved particles with the fixed spheres and cylinders (FictitiousDomain::beforeDemStep,
// the DEM's contact law with the body as a wall of its material): a sphere settling onto a fixed sphere
// comes to rest on it at the Hertz overlap of its submerged weight.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "core/parallel.hpp"
#include "core/params.hpp"

namespace gf::resolved {
namespace {

/// A particle of d = 2 mm, 1500 kg/m^3 (E = 1e5 Pa, nu = 0.3) settling from 0.15 d above a fixed sphere
/// of the same size (material rigid), centres on one vertical line, in a closed box of 3 d of liquid
/// (1000 kg/m^3, 0.01 Pa s) at 8 cells per d. Returns the surface gap over d after each fluid step of
/// 0.25 ms, and the particle's sideways offset at the end.
std::vector<double> settleOntoFixedSphere(int steps, double& sideways) {
  const std::string text = R"(
case: {name: resolved_sphere_on_sphere}
domain: {min: [0, 0, 0], max: [0.006, 0.006, 0.006]}
gravity: [0, 0, -9.81]
time: {end: 1.0, dem_step: 2.5e-5, coupling_interval: 10}
materials:
  - {name: sphere, density: 1500.0, youngs_modulus: 1.0e5, poisson_ratio: 0.3, restitution: 0.5, friction: 0.1}
insertion:
  - {type: lattice, material: sphere, origin: [0.003, 0.003, 0.0038], nx: 1, ny: 1, nz: 1, spacing: 0.004,
     diameter: 0.002}
fluid: {density: 1000.0, viscosity: 0.01, cells: [24, 24, 24]}
output: {interval: 0}
resolved:
  bodies:
    - {shape: sphere, centre: [0.003, 0.003, 0.0015], radius: 0.001}
)";
  const int threads = threadCount();  // (one thread, as the command line's --threads 1)
  setThreadCount(1);
  Params root = Params::loadString(text, "resolved_sphere_on_sphere.yaml");
  app::RunOptions options;
  options.threads = 1;
  options.quiet = true;
  app::Simulation sim(root, "resolved_sphere_on_sphere.yaml", options);
  std::vector<double> gaps;
  for (int n = 0; n < steps; ++n) {
    sim.advance();
    const dem::ParticleSet& p = sim.dem().particles();
    gaps.push_back((p.position[0].z - 0.0015 - 0.001 - p.radius[0]) / (2.0 * p.radius[0]));
    sideways = std::hypot(p.position[0].x - 0.003, p.position[0].y - 0.003);
  }
  setThreadCount(threads);
  return gaps;
}

TEST(ResolvedBodyContact, SphereRestsOnAFixedSphereAtTheHertzOverlap) {
  // Hertz: F = 4/3 E* sqrt(R*) delta^{3/2} with E* = E / (1 - nu^2) (a rigid body), R* = R / 2, F the
  // submerged weight (1500 - 1000) kg/m^3 V g: delta = 3.40e-6 m = 0.0017 d.
  constexpr int kSteps = 240;  // 60 ms: it lands after about 27 ms
  double sideways = 0.0;
  const std::vector<double> gaps = settleOntoFixedSphere(kSteps, sideways);
  for (int n = 19; n < kSteps; n += 20) std::printf("t %.4f s  gap/d %.5f\n", (n + 1) * 2.5e-4, gaps[n]);
  const double r = 0.001, weight = 500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r * 9.81;
  const double eStar = 1.0e5 / (1.0 - 0.3 * 0.3), rStar = r / 2.0;
  const double hertz = std::pow(3.0 * weight / (4.0 * eStar * std::sqrt(rStar)), 2.0 / 3.0);
  const double overlap = -gaps.back() * 2.0 * r;
  std::printf("resting overlap %.4g m, Hertz %.4g m (ratio %.4f); sideways %.3g m\n", overlap, hertz, overlap / hertz,
              sideways);
  EXPECT_NEAR(overlap, hertz, 0.03 * hertz);  // (0.5 %)
  double deepest = 0.0;
  for (double g : gaps) deepest = std::min(deepest, g);
  EXPECT_GT(deepest, -0.02);      // never sank into the body
  EXPECT_LT(sideways, 1e-3 * r);  // (symmetric: it stays on top)
}

}  // namespace
}  // namespace gf::resolved
