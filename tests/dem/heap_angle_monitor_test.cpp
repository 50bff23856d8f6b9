// heap_angle monitor (src/dem/monitors/heap_angle_monitor.cpp) on a hand-computable particle set.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/domain.hpp"
#include "core/monitor.hpp"
#include "core/params.hpp"
#include "dem/system.hpp"

namespace {

// Ten spheres (d = 2 mm) on the floor along x at radial distances 5, 15, ..., 95 mm from the axis.
const std::string kCase = R"(domain: {min: [-0.1, -0.1, 0], max: [0.1, 0.1, 0.1]}
materials: [{name: a, density: 1000.0}]
insertion:
  - {type: lattice, origin: [0.005, 0.0, 0.001], spacing: 0.01, nx: 10, ny: 1, nz: 1, diameter: 0.002}
heap: {type: heap_angle}
heap_median: {type: heap_angle, base_quantile: 0.5}
)";

TEST(HeapAngleMonitor, ConeFromARadialQuantile) {
  gf::Params root = gf::Params::loadString(kCase, "test");
  const gf::Domain domain = gf::Domain::read(root);
  gf::dem::System dem{root, domain, {0.0, 0.0, 0.0}};
  const gf::RunState state{0.0, 0, &dem, nullptr, nullptr, {}};
  gf::Params p = root.section({"heap"});
  auto heap = gf::Registry<gf::Monitor>::instance().create(p, {"type"});
  ASSERT_EQ(heap->columns().size(), 3u);
  EXPECT_EQ(heap->columns()[2].unit, "deg");
  const auto v = heap->sample(state);
  // q = 0.9 of 10 particles: the 9th smallest distance (index round(0.9 * 9) = 8), 85 mm;
  // a cone holds 90 % of its volume within r = R (1 - 0.1^(1/3)).
  const double radius = 0.085 / (1.0 - std::cbrt(0.1));
  EXPECT_NEAR(v[0], 0.002, 1e-15);  // top of the spheres
  EXPECT_NEAR(v[1], radius, 1e-12);
  EXPECT_NEAR(v[2], std::atan(0.002 / radius) * 180.0 / std::numbers::pi, 1e-9);
  gf::Params pm = root.section({"heap_median"});
  auto median = gf::Registry<gf::Monitor>::instance().create(pm, {"type"});
  EXPECT_NEAR(median->sample(state)[1], 0.055 / (1.0 - std::cbrt(0.5)), 1e-12);  // index round(4.5) = 5
}

}  // namespace
