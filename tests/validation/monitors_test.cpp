// The generic monitors used by validation items (src/app/monitors/particle_probe.cpp,
// particle_statistics.cpp) against values computed by hand from a two-particle state.
#include <gtest/gtest.h>

#include <cmath>

#include "core/domain.hpp"
#include "core/monitor.hpp"
#include "core/params.hpp"
#include "dem/system.hpp"

namespace {

const std::string kCase = R"(domain: {min: [0, 0, 0], max: [1, 1, 1]}
materials: [{name: a, density: 1000.0}]
insertion:
  - {type: lattice, origin: [0.2, 0.3, 0.4], spacing: 0.5, nx: 1, ny: 1, nz: 2, diameter: 0.1, velocity: [3.0, 0.0, -4.0]}
monitor: {type: particle_probe, id: 1}
stats: {type: particle_statistics}
stats_x: {type: particle_statistics, axis: x}
missing: {type: particle_probe, id: 7}
)";

struct TwoParticles {
  gf::Params root = gf::Params::loadString(kCase, "test");
  gf::Domain domain = gf::Domain::read(root);
  gf::dem::System dem{root, domain, {0.0, 0.0, 0.0}};
  gf::RunState state() const { return gf::RunState{0.0, 0, &dem, nullptr, nullptr, {}}; }
  std::unique_ptr<gf::Monitor> monitor(const char* section) {
    gf::Params p = root.section({section});
    return gf::Registry<gf::Monitor>::instance().create(p, {"type"});
  }
};

}  // namespace

TEST(Monitors, ParticleProbeReportsTheParticleWithThatId) {
  TwoParticles t;
  auto probe = t.monitor("monitor");
  const auto columns = probe->columns();
  ASSERT_EQ(columns.size(), 12u);
  EXPECT_EQ(columns[2].name, "z");
  EXPECT_EQ(columns[2].unit, "m");
  EXPECT_EQ(columns[5].unit, "m/s");
  const auto v = probe->sample(t.state());
  ASSERT_EQ(v.size(), columns.size());
  EXPECT_DOUBLE_EQ(v[0], 0.2);
  EXPECT_DOUBLE_EQ(v[2], 0.9);  // id 1 is the second lattice point: 0.4 + 0.5
  EXPECT_DOUBLE_EQ(v[3], 3.0);
  EXPECT_DOUBLE_EQ(v[5], -4.0);
  for (double x : t.monitor("missing")->sample(t.state())) EXPECT_TRUE(std::isnan(x));
}

TEST(Monitors, ParticleStatisticsAlongAnAxis) {
  TwoParticles t;
  auto stats = t.monitor("stats");
  const auto columns = stats->columns();
  ASSERT_EQ(columns.size(), 8u);
  EXPECT_EQ(columns[2].name, "z_max");
  EXPECT_EQ(columns[5].unit, "J");
  const auto v = stats->sample(t.state());
  const double mass = 1000.0 * M_PI / 6.0 * 0.1 * 0.1 * 0.1;
  EXPECT_EQ(v[0], 2.0);
  EXPECT_DOUBLE_EQ(v[1], 0.4);
  EXPECT_DOUBLE_EQ(v[2], 0.9);
  EXPECT_DOUBLE_EQ(v[3], 0.65);
  EXPECT_DOUBLE_EQ(v[4], 0.95);                       // top = 0.9 + r
  EXPECT_NEAR(v[5], 2 * 0.5 * mass * 25.0, 1e-15);   // |v| = 5 m/s
  EXPECT_DOUBLE_EQ(v[6], 5.0);
  EXPECT_DOUBLE_EQ(v[7], 5.0);
  auto alongX = t.monitor("stats_x");
  EXPECT_EQ(alongX->columns()[1].name, "x_min");
  EXPECT_DOUBLE_EQ(alongX->sample(t.state())[3], 0.2);
}
