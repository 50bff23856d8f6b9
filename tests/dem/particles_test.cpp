// ParticleSet: the layout stamp changes with the particles or their order, and only then; the
// registered columns travel with their particles.
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

TEST(ParticleSet, ColumnsFollowTheirParticlesThroughGatherAddAndLoad) {
  // Columns registered by another subsystem (the coupler's per-particle state) travel with their
  // particle: gather reorders and drops them with the particles, add appends the fill value.
  ParticleSet p = threeParticles();
  const std::size_t beta = p.addColumn("test.beta", -1.0);
  const std::size_t slip = p.addColumn("test.slip", Vec3{0.0, 0.0, 7.0});
  EXPECT_EQ(p.addColumn("test.beta", 5.0), beta);  // registered once, by name
  EXPECT_EQ(p.findDoubleColumn("test.beta"), beta);
  EXPECT_EQ(p.findVec3Column("test.beta"), ParticleSet::kNoColumn);
  EXPECT_EQ(p.findDoubleColumn("absent"), ParticleSet::kNoColumn);
  EXPECT_EQ(p.doubleColumns[beta].values, (std::vector<double>{-1.0, -1.0, -1.0}));
  const std::uint64_t stamp = p.layoutStamp;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.doubleColumns[beta].values[i] = 100.0 + static_cast<double>(p.id[i]);
    p.vec3Columns[slip].values[i] = {static_cast<double>(p.id[i]), 0.0, 0.0};
  }
  EXPECT_EQ(p.layoutStamp, stamp);  // (values, not the layout)
  p.add(13, 0, 0.001, 2500.0, {});
  EXPECT_EQ(p.doubleColumns[beta].values.back(), -1.0);
  EXPECT_EQ(p.vec3Columns[slip].values.back(), (Vec3{0.0, 0.0, 7.0}));
  p.reserve(10);
  // Morton-like reordering with a removal (an outlet): new k holds old order[k]
  p.gather({3, 2, 0});
  EXPECT_EQ(p.id, (std::vector<std::int64_t>{13, 12, 10}));
  EXPECT_EQ(p.doubleColumns[beta].values, (std::vector<double>{-1.0, 112.0, 110.0}));
  EXPECT_EQ(p.vec3Columns[slip].values, (std::vector<Vec3>{{0.0, 0.0, 7.0}, {12.0, 0.0, 0.0}, {10.0, 0.0, 0.0}}));
  const ParticleSet copy = p;  // a copy carries them
  EXPECT_EQ(copy.doubleColumns[beta].values, p.doubleColumns[beta].values);
  // load restores the particles; the columns stay registered, at their fill values (their owner
  // restores its own state)
  BinaryWriter out;
  threeParticles().save(out);
  BinaryReader in(out.bytes().data(), out.bytes().size());
  p.load(in);
  EXPECT_EQ(p.doubleColumns[beta].values, (std::vector<double>{-1.0, -1.0, -1.0}));
  EXPECT_EQ(p.vec3Columns[slip].values.size(), 3u);
}

}  // namespace
}  // namespace gf::dem
