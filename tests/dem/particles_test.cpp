// ParticleSet: the layout stamp changes with the particles or their order, and only then.
#include <gtest/gtest.h>

#include <set>

#include "core/serialize.hpp"
#include "dem/particles.hpp"

namespace gf::dem {
namespace {

ParticleSet threeParticles() {
  ParticleSet p;
  for (int i = 0; i < 3; ++i) p.add(10 + i, 0, 0.001, 2500.0, {0.01 * i, 0.0, 0.0});
  return p;
}

TEST(ParticleSet, LayoutStampFollowsIdsAndOrder) {
  ParticleSet p = threeParticles();
  const ParticleSet copy = p;  // same particles, same order: same stamp
  EXPECT_EQ(copy.layoutStamp, p.layoutStamp);
  EXPECT_NE(p.layoutStamp, 0u);
  std::set<std::uint64_t> seen{p.layoutStamp, ParticleSet{}.layoutStamp, threeParticles().layoutStamp};
  EXPECT_EQ(seen.size(), 3u);  // every new set its own

  // Moving, pushing and sizing change no id and no order: the stamp stays.
  const std::uint64_t before = p.layoutStamp;
  p.position[1].x += 1.0;
  p.velocity[2].z = 3.0;
  p.force[0] = {1, 2, 3};
  p.enableExternalForces();
  p.reserve(100);
  EXPECT_EQ(p.layoutStamp, before);

  // Each of add, gather (reorder, removal) and load gives a fresh one.
  std::set<std::uint64_t> stamps{p.layoutStamp};
  p.add(99, 0, 0.001, 2500.0, {});
  stamps.insert(p.layoutStamp);
  p.gather({3, 2, 1, 0});
  stamps.insert(p.layoutStamp);
  p.gather({0, 1});
  stamps.insert(p.layoutStamp);
  BinaryWriter out;
  p.save(out);
  BinaryReader in(out.bytes().data(), out.bytes().size());
  ParticleSet loaded = threeParticles();
  const std::uint64_t beforeLoad = loaded.layoutStamp;
  loaded.load(in);
  EXPECT_NE(loaded.layoutStamp, beforeLoad);
  stamps.insert(loaded.layoutStamp);
  EXPECT_EQ(stamps.size(), 5u);
  EXPECT_EQ(loaded.id, (std::vector<std::int64_t>{99, 12}));
  p.touchLayout();
  EXPECT_EQ(stamps.count(p.layoutStamp), 0u);
}

}  // namespace
}  // namespace gf::dem
