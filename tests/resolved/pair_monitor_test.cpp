// Monitor resolved_particle_pair (src/resolved/pair_monitor.cpp): the phases of drafting, kissing
// and tumbling of a prescribed pair trajectory, their times interpolated between samples.
#include <gtest/gtest.h>

#include <cmath>

#include "core/monitor.hpp"
#include "core/params.hpp"
#include "dem/particles.hpp"

namespace gf::resolved {
namespace {

TEST(ResolvedPairMonitor, DraftingKissingTumblingInOrderWithInterpolatedTimes) {
  Params p = Params::loadString("{type: resolved_particle_pair, particle_id: 0, other_id: 1}\n", "monitor.yaml");
  auto m = Registry<Monitor>::instance().create(p, {"type"});
  ASSERT_TRUE(m);
  dem::ParticleSet set;
  const double d = 0.002;
  set.add(0, 0, 0.5 * d, 1000.0, Vec3{0, 0, 0.0});     // leading (lower)
  set.add(1, 0, 0.5 * d, 1000.0, Vec3{0, 0, 2.0 * d});  // trailing, gap 1 d
  RunState st;
  st.particles = &set;
  st.gravity = Vec3{0, 0, -9.81};
  // Both fall at 1 cm/s; the trailing one at 3 cm/s from t = 0.1 s (gap closes at 2 cm/s: d / 0.02 =
  // 0.1 s to contact, at t = 0.2 s); after contact the pair turns about its lower sphere at 10 rad/s
  // (separation = cos(theta), below 0.1 at theta = acos(0.1)).
  const double dt = 0.01;
  double contactAngle0 = -1.0;
  std::vector<double> row;
  for (int n = 0; n <= 40; ++n) {
    const double t = n * dt;
    st.time = t;
    const double zLead = -0.01 * t;
    set.position[0] = Vec3{0, 0, zLead};
    set.velocity[0] = Vec3{0, 0, -0.01};
    if (t <= 0.2 + 1e-12) {
      const double gap = t <= 0.1 ? d : d - 0.02 * (t - 0.1);
      set.position[1] = Vec3{0, 0, zLead + d + gap};
      set.velocity[1] = Vec3{0, 0, t < 0.1 ? -0.01 : -0.03};
    } else {
      if (contactAngle0 < 0.0) contactAngle0 = t;
      const double theta = 10.0 * (t - 0.2);
      set.position[1] = Vec3{d * std::sin(theta), 0, zLead + d * std::cos(theta)};
      set.velocity[1] = Vec3{0, 0, -0.01};
    }
    row = m->sample(st);
  }
  ASSERT_EQ(row.size(), 8u);
  EXPECT_NEAR(row[4], 0.115, 0.0051);  // drafting: the first sample with the gap closed by 10 % (t = 0.11 s or, round-off, 0.12 s)
  // contact: gap 0.05 d reached at t = 0.2 - 0.05 d / 0.02 = 0.195 s (linear in time: exact)
  EXPECT_NEAR(row[5], 0.195, 1e-9);
  // tumbling: cos(10 (t - 0.2)) = 0.1 at t = 0.3471 s; linear between the samples at 0.34 and 0.35
  const double exact = 0.2 + std::acos(0.1) / 10.0;
  EXPECT_NEAR(row[6], exact, 2e-4);
  EXPECT_EQ(row[7], 1.0);
  EXPECT_NEAR(row[1], std::cos(10.0 * 0.2), 1e-9);  // separation over d at t = 0.4 s
}

}  // namespace
}  // namespace gf::resolved
