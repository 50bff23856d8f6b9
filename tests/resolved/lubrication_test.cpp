// The lubrication correction of resolved spheres (src/resolved/lubrication.hpp): the formula against
// its closed form, zero at and beyond the range and continuous there, the step-mean force bounded by
// the approach it can stop; and a sphere settling onto a wall approaches it more slowly with it.
#include "resolved/lubrication.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "../app/run_helper.hpp"
#include "app/simulation.hpp"
#include "core/parallel.hpp"
#include "core/params.hpp"

namespace gf::resolved {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(ResolvedLubrication, CoefficientIsTheSqueezeFilmTermLessItsValueAtTheRange) {
  // Two spheres of 1 and 2 mm in a liquid of 0.01 Pa s: R_eff = 2/3 mm; range 0.1 mm, cut-off 1 um.
  const double mu = 0.01, r1 = 1e-3, r2 = 2e-3, range = 1e-4, cutoff = 1e-6;
  const double reff = reducedRadius(r1, r2);
  EXPECT_NEAR(reff, 2e-3 / 3.0, 1e-18);
  EXPECT_EQ(reducedRadius(r1, std::numeric_limits<double>::infinity()), r1);  // a wall
  for (double h : {2e-6, 1e-5, 5e-5, 9.9e-5}) {
    const double closed = 6.0 * kPi * mu * reff * reff * (1.0 / h - 1.0 / range);
    EXPECT_NEAR(lubricationCoefficient(mu, reff, h, range, cutoff), closed, 1e-12 * closed) << h;
  }
  // Sphere-wall: 6 pi mu R^2 (1/h - 1/h_range).
  const double h = 3e-5, wall = 6.0 * kPi * mu * r1 * r1 * (1.0 / h - 1.0 / range);
  EXPECT_NEAR(lubricationCoefficient(mu, reducedRadius(r1, std::numeric_limits<double>::infinity()), h, range, cutoff),
              wall, 1e-12 * wall);
}

TEST(ResolvedLubrication, VanishesAtAndBeyondTheRangeAndIsContinuousThere) {
  const double mu = 1e-3, reff = 5e-4, range = 2e-4, cutoff = 2e-6;
  EXPECT_EQ(lubricationCoefficient(mu, reff, range, range, cutoff), 0.0);
  EXPECT_EQ(lubricationCoefficient(mu, reff, 1.5 * range, range, cutoff), 0.0);
  EXPECT_EQ(lubricationCoefficient(mu, reff, 1.0, range, cutoff), 0.0);
  // Just inside: of the order of the slope times the distance (no jump).
  const double slope = 6.0 * kPi * mu * reff * reff / (range * range);  // -dc/dh at the range
  for (double eps : {1e-3, 1e-6, 1e-9}) {
    const double c = lubricationCoefficient(mu, reff, range * (1.0 - eps), range, cutoff);
    EXPECT_GT(c, 0.0);
    EXPECT_NEAR(c, slope * range * eps, 2e-3 * slope * range * eps + 1e-30) << eps;
  }
  // Below the cut-off it stays at its value there; in contact (h <= 0) the DEM's contact law acts.
  const double atCutoff = lubricationCoefficient(mu, reff, cutoff, range, cutoff);
  EXPECT_EQ(lubricationCoefficient(mu, reff, 0.5 * cutoff, range, cutoff), atCutoff);
  EXPECT_EQ(lubricationCoefficient(mu, reff, 0.0, range, cutoff), 0.0);
  EXPECT_EQ(lubricationCoefficient(mu, reff, -1e-5, range, cutoff), 0.0);
  // Decreasing in h between the cut-off and the range.
  double previous = atCutoff;
  for (double h = 1.5 * cutoff; h < range; h *= 1.5) {
    const double c = lubricationCoefficient(mu, reff, h, range, cutoff);
    EXPECT_LT(c, previous) << h;
    previous = c;
  }
}

TEST(ResolvedLubrication, StepMeanForceIsTheFormulaWhenWeakAndNeverReversesTheApproach) {
  const double m = 1e-5, dt = 1e-3, vn = -0.02;  // approaching at 2 cm/s
  // Weak film (c dt / m = 1e-4): -c v_n to 5e-5 relative (the next term of the exponential).
  const double weak = 1e-6;
  EXPECT_NEAR(lubricationForce(weak, vn, m, dt), -weak * vn, 6e-5 * weak * std::abs(vn));
  EXPECT_GT(lubricationForce(weak, vn, m, dt), 0.0);  // pushes the particle away (along n)
  EXPECT_LT(lubricationForce(weak, -vn, m, dt), 0.0);  // resists the separation too
  // Stiff film (c dt / m = 100): the force that stops the approach within the step, not more.
  const double stiff = 1.0;
  EXPECT_NEAR(lubricationForce(stiff, vn, m, dt), -m * vn / dt, 1e-12 * m * std::abs(vn) / dt);
  for (double c : {1e-7, 1e-5, 1e-3, 1e-1, 1e1})
    EXPECT_LE(lubricationForce(c, vn, m, dt) * dt / m, -vn * (1.0 + 1e-12)) << c;
  EXPECT_EQ(lubricationForce(0.0, vn, m, dt), 0.0);
}

/// A sphere of d = 2 mm, 1500 kg/m^3, settling from rest onto the bottom of a closed box of 3 d x 3 d
/// x 3 d of liquid (0.01 Pa s) at 8 cells per diameter, its lowest point 0.3 d above the wall
/// (a DEM plane at z = 0).
std::string wallApproachCase(bool lubrication) {
  return std::string(R"(
case: {name: resolved_wall_approach}
domain: {min: [0, 0, 0], max: [0.006, 0.006, 0.006]}
gravity: [0, 0, -9.81]
time: {end: 1.0, dem_step: 2.5e-5, coupling_interval: 10}
materials:
  - {name: sphere, density: 1500.0, youngs_modulus: 1.0e5, poisson_ratio: 0.3, restitution: 0.5, friction: 0.1}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1]}
insertion:
  - {type: lattice, material: sphere, origin: [0.003, 0.003, 0.0016], nx: 1, ny: 1, nz: 1, spacing: 0.004,
     diameter: 0.002}
fluid:
  density: 1000.0
  viscosity: 0.01
  cells: [24, 24, 24]
output: {interval: 0}
resolved:
  lubrication: {enabled: )") +
         (lubrication ? "true" : "false") + R"(, range: 0.1, min_gap: 0.001}
)";
}

/// Gap over d after each fluid step.
std::vector<double> wallApproach(bool lubrication, int steps) {
  const int threads = threadCount();  // (one thread, as the command line's --threads 1)
  setThreadCount(1);
  Params root = Params::loadString(wallApproachCase(lubrication), "resolved_wall_approach.yaml");
  app::RunOptions options;
  options.threads = 1;
  options.quiet = true;
  app::Simulation sim(root, "resolved_wall_approach.yaml", options);
  std::vector<double> gaps;
  for (int n = 0; n < steps; ++n) {
    sim.advance();
    const dem::ParticleSet& p = sim.dem().particles();
    gaps.push_back((p.position[0].z - p.radius[0]) / (2.0 * p.radius[0]));
  }
  setThreadCount(threads);
  return gaps;
}

TEST(ResolvedLubrication, SphereSettlingOntoAWallApproachesItMoreSlowlyWithIt) {
  // 200 fluid steps of 0.25 ms (Re about 4 at the approach). Measured: without the correction the
  // sphere touches the wall after 0.0413 s; with it the gap is 0.016 d at 0.0425 s and still 0.0067 d
  // at 0.05 s (it closes about exponentially, the film's resistance growing as 1 / h).
  constexpr int kSteps = 200;
  const std::vector<double> off = wallApproach(false, kSteps), on = wallApproach(true, kSteps);
  for (int n = 9; n < kSteps; n += 10) std::printf("t %.4f s  gap/d without %.4f  with %.4f\n", (n + 1) * 2.5e-4, off[n], on[n]);
  // Identical until the gap falls below the range (0.1 d); then the sphere with the correction is
  // higher at every step.
  int first = -1, touch = -1;
  for (int n = 0; n < kSteps; ++n) {
    if (off[n] >= 0.1) {
      EXPECT_EQ(on[n], off[n]) << n;
    } else if (first < 0) {
      first = n;
    }
    if (touch < 0 && off[n] <= 0.0) touch = n;
  }
  ASSERT_GE(first, 0) << "the sphere did not come within the range";
  for (int n = first + 2; n < kSteps; ++n) EXPECT_GT(on[n], off[n]) << n;
  ASSERT_GE(touch, 0) << "without the correction the sphere did not reach the wall";
  EXPECT_GT(on[touch], 0.01);
  EXPECT_GT(on.back(), 0.0);
}

TEST(ResolvedLubrication, CutOffAtOrAboveTheRangeIsRefused) {
  gf::testing::TempDir dir;
  std::string text = wallApproachCase(true);
  const std::string from = "range: 0.1, min_gap: 0.001";
  ASSERT_NE(text.find(from), std::string::npos);
  text.replace(text.find(from), from.size(), "range: 0.05, min_gap: 0.05");
  const auto r = gf::testing::grainflow("check " + dir.write("lubrication.yaml", text));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("resolved.lubrication.min_gap"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("a cut-off below resolved.lubrication.range"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gf::resolved
