// Angle of repose of a heap formed by a collapsing column on a rough floor: reported, and
// increasing with the rolling friction mu_r (monotonic check; no absolute reference value).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

/// Heap angle atan(H / R): H = height of the heap top above the floor, R = radius around the
/// heap axis containing 95 % of the particles.
double reposeAngleDegrees(double rollingFriction) {
  const std::string yaml = test::materialsYaml("hertz_mindlin", 0.3, 0.5, 1e7, 0.3,
                                               fmt::format("  rolling: constant_torque\n  rolling_friction: {}",
                                                           rollingFriction)) +
                           R"(
domain: {min: [-0.06, -0.06, 0], max: [0.06, 0.06, 0.08]}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1]}
insertion:
  - {type: random_packing, min: [-0.006, -0.006, 0.0], max: [0.006, 0.006, 0.07], count: 400, seed: 8,
     size: {diameter: 0.002}}
)";
  test::DemCase c(yaml, {0, 0, -9.81});
  for (int k = 0; k < 35000; ++k) c->step(1e-5);
  const ParticleSet& p = c->particles();
  std::vector<double> radial;
  double top = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    radial.push_back(std::hypot(p.position[i].x, p.position[i].y));
    top = std::max(top, p.position[i].z + p.radius[i]);
  }
  std::sort(radial.begin(), radial.end());
  const double base = radial[static_cast<std::size_t>(0.95 * (radial.size() - 1))];
  return std::atan2(top, base) * 180.0 / std::numbers::pi;
}

TEST(DemRepose, HeapAngleIncreasesWithRollingFriction) {
  const double a0 = reposeAngleDegrees(0.0), a1 = reposeAngleDegrees(0.1), a2 = reposeAngleDegrees(0.4);
  std::printf("[ repose ] heap angle: mu_r = 0: %.1f deg, 0.1: %.1f deg, 0.4: %.1f deg\n", a0, a1, a2);
  EXPECT_LT(a0, a1);
  EXPECT_LT(a1, a2);
  EXPECT_GT(a2, 10.0);
}

}  // namespace
}  // namespace gf::dem
