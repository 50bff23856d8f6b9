// Neighbour search, contact history across rebuilds/reordering, determinism, restarts, energy.
#include <gtest/gtest.h>

#include <limits>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <set>

#include "core/parallel.hpp"
#include "dem/neighbour_list.hpp"
#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

using test::DemCase;
using test::materialsYaml;

ParticleSet randomParticles(std::size_t n, const Vec3& size, std::uint64_t seed) {
  ParticleSet p;
  Random rng(seed);
  for (std::size_t i = 0; i < n; ++i)
    p.add(static_cast<std::int64_t>(i), 0, rng.uniform(0.0008, 0.0012), 2500,
          {rng.uniform(0, size.x), rng.uniform(0, size.y), rng.uniform(0, size.z)});
  return p;
}

std::set<std::pair<std::int64_t, std::int64_t>> listPairs(const NeighbourList& list, const ParticleSet& p) {
  std::set<std::pair<std::int64_t, std::int64_t>> out;
  for (std::size_t i = 0; i < list.rows(); ++i)
    for (std::uint32_t k = list.rowStart[i]; k < list.rowStart[i + 1]; ++k) {
      const std::int64_t a = p.id[i], b = p.id[list.partner[k]];
      out.insert({std::min(a, b), std::max(a, b)});
    }
  return out;
}

// Pairs (i, j), i < j, closer than r_i + r_j + skin (minimum image): what a list must hold.
std::set<std::pair<std::int64_t, std::int64_t>> bruteForcePairs(const ParticleSet& p, const PeriodicBox& box,
                                                                 double skin) {
  std::set<std::pair<std::int64_t, std::int64_t>> out;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double cut = p.radius[i] + p.radius[j] + skin;
      if (normSquared(box.minimumImage(p.position[i] - p.position[j])) < cut * cut) out.insert({i, j});
    }
  return out;
}

// The 12 x 10 x 20 mm box of the list tests, periodic along the given axes.
Domain listTestBox(std::array<bool, 3> periodic) {
  Domain d;
  d.min = {0, 0, 0};
  d.max = {0.012, 0.01, 0.02};
  d.periodic = periodic;
  return d;
}

TEST(DemNeighbourList, MatchesBruteForceWithPeriodicBoundaries) {
  for (bool periodic : {false, true}) {
    const Domain d = listTestBox({periodic, false, periodic});
    const PeriodicBox box(d);
    const ParticleSet p = randomParticles(600, d.max, 7);
    const double skin = 0.0003;
    NeighbourList list;
    list.build(p, box, d.min, d.max, skin, {}, false);
    const auto expected = bruteForcePairs(p, box, skin);
    EXPECT_EQ(listPairs(list, p), expected) << "periodic=" << periodic;
    EXPECT_GT(expected.size(), 100u);
  }
}

// Each row holds its partners j > i strictly ascending (the force loop reads a row's last entry as
// its largest partner), on both sorting paths: short rows (by rank) and the long row of a large
// sphere among small ones (by insertion); the pairs are those of a brute-force search.
TEST(DemNeighbourList, RowsAreStrictlyAscendingOnBothSortingPaths) {
  const Domain d = listTestBox({false, false, false});
  const PeriodicBox box(d);
  ParticleSet p;
  p.add(0, 0, 0.003, 2500, {0.006, 0.005, 0.01});  // row 0: every neighbour of the large sphere
  const ParticleSet small = randomParticles(800, d.max, 11);
  for (std::size_t i = 0; i < small.size(); ++i)
    p.add(static_cast<std::int64_t>(i + 1), 0, small.radius[i], 2500, small.position[i]);
  const double skin = 0.0003;
  NeighbourList list;
  list.build(p, box, d.min, d.max, skin, {}, false);
  std::size_t longest = 0, shortRows = 0;
  for (std::size_t i = 0; i < list.rows(); ++i) {
    const std::uint32_t first = list.rowStart[i], last = list.rowStart[i + 1];
    longest = std::max<std::size_t>(longest, last - first);
    shortRows += last - first >= 2 && last - first <= 16 ? 1 : 0;
    for (std::uint32_t k = first; k < last; ++k) {
      EXPECT_GT(list.partner[k], i) << "row " << i;
      if (k > first) {
        EXPECT_LT(list.partner[k - 1], list.partner[k]) << "row " << i << " entry " << k - first;
      }
    }
  }
  EXPECT_GT(longest, 16u);    // the insertion-sort path ran
  EXPECT_GT(shortRows, 100u);  // and the rank path, on many rows of several entries
  EXPECT_EQ(listPairs(list, p), bruteForcePairs(p, box, skin));
}

// On a team, build() counts the touching pairs of each row as it lists them; countTouching() (a
// restart's count) gives the same numbers, periodic or not.
TEST(DemNeighbourList, BuildCountsTouchingPairsAsCountTouching) {
  setThreadCount(2);
  for (bool periodic : {false, true}) {
    const Domain d = listTestBox({periodic, periodic, false});
    const PeriodicBox box(d);
    const ParticleSet p = randomParticles(3000, d.max, 5);
    NeighbourList list;
    list.build(p, box, d.min, d.max, 0.0003, {}, false);
    const std::vector<std::uint32_t> counted = list.touchingStart;
    EXPECT_EQ(counted.size(), p.size() + 1);
    list.countTouching(p.position, p.radius, box);
    EXPECT_EQ(counted, list.touchingStart) << "periodic=" << periodic;
    EXPECT_GT(counted.back(), 500u);                  // overlapping random spheres touch
    EXPECT_LT(counted.back(), list.entries());        // and not every listed pair does
  }
  setThreadCount(1);
}

// The AVX-512 candidate test (where the CPU has it) and the generic one build the same lists: row
// starts, partners and touching counts, periodic along none, some or all axes, on 1 and 2 threads
// (the touching count runs on teams only), with ranges longer than one vector (a dense random bed
// of small spheres and a large sphere's long row).
TEST(DemNeighbourList, Avx512AndGenericCandidateTestsBuildTheSameLists) {
  for (int threads : {1, 2}) {
    setThreadCount(threads);
    for (const std::array<bool, 3> periodic :
         {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true},
          std::array<bool, 3>{true, true, true}}) {
      const Domain d = listTestBox(periodic);
      const PeriodicBox box(d);
      ParticleSet p = randomParticles(4000, d.max, 13);
      p.add(4000, 0, 0.003, 2500, {0.006, 0.005, 0.01});
      NeighbourList lists[2];
      for (int generic = 0; generic < 2; ++generic) {
        allowNeighbourAvx512(generic == 0);
        lists[generic].build(p, box, d.min, d.max, 0.0004, {}, false);
      }
      allowNeighbourAvx512(true);
      const std::string where = "threads " + std::to_string(threads) + ", periodic " +
                                std::to_string(periodic[0]) + std::to_string(periodic[1]) + std::to_string(periodic[2]);
      EXPECT_EQ(lists[0].rowStart, lists[1].rowStart) << where;
      EXPECT_EQ(lists[0].partner, lists[1].partner) << where;
      EXPECT_EQ(lists[0].touchingStart, lists[1].touchingStart) << where;
      EXPECT_EQ(listPairs(lists[0], p), bruteForcePairs(p, box, 0.0004)) << where;
      EXPECT_GT(lists[0].entries(), 10000u) << where;
    }
  }
  setThreadCount(1);
}

// Morton order: by the interleaved cell bits, ties (particles in one cell) by index; the same
// order as a comparison sort of (key, index), also for keys of many bits (a tall box of 2^11
// cells along z).
TEST(DemNeighbourList, MortonOrderSortsByKeyThenIndex) {
  const Vec3 lo{0, 0, 0}, hi{0.01, 0.01, 2.048};
  Random rng(9);
  std::vector<Vec3> x(5000);
  for (Vec3& v : x) v = {rng.uniform(0, hi.x), rng.uniform(0, hi.y), rng.uniform(0, hi.z)};
  for (int k = 0; k < 50; ++k) x[100 + k] = x[7];  // ties
  const double h = 0.001;
  std::vector<std::uint64_t> key(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      const auto c = static_cast<std::uint64_t>(std::floor((x[i][a] - lo[a]) / h));
      for (int bit = 0; bit < 21; ++bit) key[i] |= ((c >> bit) & 1u) << (3 * bit + a);
    }
  std::vector<std::uint32_t> expected(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) expected[i] = static_cast<std::uint32_t>(i);
  std::sort(expected.begin(), expected.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  EXPECT_EQ(mortonOrder(x, lo, hi, h), expected);
  EXPECT_GT(*std::max_element(key.begin(), key.end()), std::uint64_t{1} << 32);  // passes beyond 32 bits
}

TEST(DemNeighbourList, HistorySurvivesReorderingRemovalAndInsertion) {
  Domain d;
  d.min = {0, 0, 0};
  d.max = {0.01, 0.01, 0.01};
  const PeriodicBox box(d);
  ParticleSet p = randomParticles(300, d.max, 3);
  NeighbourList list;
  list.build(p, box, d.min, d.max, 0.0005, {}, true);
  // History value encodes the ordered pair of ids: i's view of (id_i, id_j).
  auto code = [](std::int64_t a, std::int64_t b) { return Vec3{double(a), double(b), double(a - b)}; };
  for (std::size_t i = 0; i < list.rows(); ++i)
    for (std::uint32_t k = list.rowStart[i]; k < list.rowStart[i + 1]; ++k) {
      list.tangentialHistory[k] = code(p.id[i], p.id[list.partner[k]]);
      list.rollingHistory[k] = 2.0 * list.tangentialHistory[k];
    }
  // Morton order, drop every 7th particle, append 5 new ones.
  std::vector<std::uint32_t> order = mortonOrder(p.position, d.min, d.max, 0.002);
  std::erase_if(order, [](std::uint32_t i) { return i % 7 == 0; });
  const std::size_t listed = p.size();
  p.gather(order);
  for (int k = 0; k < 5; ++k) p.add(1000 + k, 0, 0.001, 2500, {0.001 * k + 0.002, 0.005, 0.005});
  std::vector<std::int64_t> previous(p.size(), -1);
  for (std::size_t k = 0; k < order.size(); ++k) previous[k] = order[k] < listed ? order[k] : -1;
  list.build(p, box, d.min, d.max, 0.0005, previous, true);
  std::size_t carried = 0;
  for (std::size_t i = 0; i < list.rows(); ++i)
    for (std::uint32_t k = list.rowStart[i]; k < list.rowStart[i + 1]; ++k) {
      const std::int64_t a = p.id[i], b = p.id[list.partner[k]];
      if (a >= 1000 || b >= 1000) {
        EXPECT_EQ(list.tangentialHistory[k], Vec3{});
        continue;
      }
      // i's view of (a, b): the stored code of (a, b), or minus the code of (b, a).
      const Vec3 h = list.tangentialHistory[k];
      const bool ok = h == code(a, b) || h == -code(b, a);
      EXPECT_TRUE(ok) << a << " " << b;
      EXPECT_EQ(list.rollingHistory[k], 2.0 * h);
      ++carried;
    }
  EXPECT_GT(carried, 100u);
}

std::string bedCase(int threads, const std::string& extraContact = "") {
  return materialsYaml("hertz_mindlin", 0.5, 0.5, 1e7, 0.3, extraContact) + R"(
domain: {min: [0, 0, 0], max: [0.012, 0.012, 0.03], periodic: [1, 0, 0]}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1]}
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0]}
  - {type: plane, point: [0, 0.012, 0], normal: [0, -1, 0]}
insertion:
  - type: random_packing
    min: [0, 0, 0.001]
    max: [0.012, 0.012, 0.029]
    count: 300
    seed: 5
    size: {distribution: log_normal, median_diameter: 0.0015, sigma: 0.15}
    velocity: [0.1, 0, -0.2]
neighbour_search: {reorder_interval: 2}
)";
}

std::vector<char> snapshot(const System& s) {
  BinaryWriter w;
  s.save(w);
  return w.bytes();
}

TEST(DemSystem, SameInputSameThreadsGivesBitIdenticalState) {
  const std::string yaml = bedCase(2, "  rolling: epsd\n  rolling_friction: 0.1\n  cohesion: simplified_jkr\n"
                                      "  cohesion_energy_density: 1000");
  for (int threads : {1, 2}) {
    setThreadCount(threads);
    DemCase a(yaml, {0, 0, -9.81}), b(yaml, {0, 0, -9.81});
    for (int s = 0; s < 600; ++s) {
      a->step(2e-5);
      b->step(2e-5);
    }
    EXPECT_GT(a->rebuilds(), 3);
    EXPECT_EQ(snapshot(*a), snapshot(*b)) << threads << " threads";
  }
  setThreadCount(1);
}

// A bed of identical spheres takes the sweep's shortcut (radius, mass, type, 1/m and 1/I read at
// particle 0: System::identicalSpheres): bit-identical to reading every particle's values, with
// walls, rolling history and cohesion, on one thread and on two (deferred kicks of the rows that
// receive partner forces). A different sphere ends the shortcut.
TEST(DemSystem, IdenticalSpheresShortcutChangesNoBit) {
  std::string yaml = bedCase(1, "  rolling: epsd\n  rolling_friction: 0.1\n  cohesion: simplified_jkr\n"
                                "  cohesion_energy_density: 1000");
  const std::string logNormal = "{distribution: log_normal, median_diameter: 0.0015, sigma: 0.15}";
  ASSERT_NE(yaml.find(logNormal), std::string::npos);
  yaml.replace(yaml.find(logNormal), logNormal.size(), "{distribution: constant, diameter: 0.0015}");
  {
    DemCase polydisperse(bedCase(1), {0, 0, -9.81});
    EXPECT_FALSE(polydisperse->identicalSpheres());
  }
  for (int threads : {1, 2}) {
    setThreadCount(threads);
    DemCase shortcut(yaml, {0, 0, -9.81}), everyParticle(yaml, {0, 0, -9.81});
    everyParticle->setIdenticalSpheresShortcut(false);
    EXPECT_TRUE(shortcut->identicalSpheres());
    EXPECT_FALSE(everyParticle->identicalSpheres());
    for (int s = 0; s < 3000; ++s) {
      shortcut->step(2e-5);
      everyParticle->step(2e-5);
    }
    EXPECT_GT(shortcut->rebuilds(), 3);
    EXPECT_GT(shortcut->contactStatistics().particleContacts, 100);
    EXPECT_GT(shortcut->contactStatistics().wallContacts, 10);
    EXPECT_EQ(snapshot(*shortcut), snapshot(*everyParticle)) << threads << " threads";
    // One sphere of another radius (same density: another mass too) ends the shortcut.
    shortcut->particles().add(100000, 0, 0.0005, 2500, {0.006, 0.006, 0.028});
    shortcut->refresh();
    EXPECT_FALSE(shortcut->identicalSpheres());
  }
  setThreadCount(1);
}

// Every force is summed in the one-thread order on any split (PartnerBuffers: the contributions
// to the rows that receive from earlier blocks are logged and added after the barrier in row
// order), so two and three threads, with equal, skewed or measured splits, give the bits of one
// thread: a touching lattice in a box (contacts everywhere within a few steps) and the periodic
// polydisperse bed with plane walls, rolling history and cohesion. With three threads the last
// block receives from two earlier blocks.
TEST(DemSystem, AnyThreadCountAndSplitGivesTheOneThreadBits) {
  const std::string lattice = materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [0, 0, 0], max: [0.014, 0.014, 0.03]}
walls:
  - {type: box, min: [0, 0, 0], max: [0.014, 0.014, 0.03]}
insertion:
  - {type: lattice, origin: [0.001, 0.001, 0.001], spacing: 0.002, nx: 7, ny: 7, nz: 7, diameter: 0.002}
)";
  const std::string bed = bedCase(1, "  rolling: epsd\n  rolling_friction: 0.1\n  cohesion: simplified_jkr\n"
                                     "  cohesion_energy_density: 1000");
  struct Split {
    int team;
    std::vector<double> speeds;  // empty: measured
  };
  const std::vector<Split> splits = {{2, {1.0, 1.0}}, {2, {0.5, 2.0}}, {2, {2.0, 0.5}}, {2, {}},
                                     {3, {0.6, 1.7, 0.7}}, {3, {}}};
  for (const std::string* caseYaml : {&lattice, &bed}) {
    const std::string& yaml = *caseYaml;
    const bool isLattice = caseYaml == &lattice;
    auto start = [&](System& sys) {
      if (!isLattice) return;
      Random rng(5);
      for (Vec3& v : sys.particles().velocity) v = {rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)};
      sys.refresh();
    };
    const int steps = isLattice ? 300 : 3000;
    setThreadCount(1);
    DemCase one(yaml, {0, 0, -9.81});
    start(*one);
    for (int s = 0; s < steps; ++s) one->step(2e-5);
    EXPECT_GT(one->contactStatistics().particleContacts, isLattice ? 500 : 100);
    EXPECT_GT(one->contactStatistics().wallContacts, 10);
    EXPECT_GT(one->rebuilds(), isLattice ? 0 : 3);
    const std::vector<char> reference = snapshot(*one);
    for (const Split& split : splits) {
      setThreadCount(split.team);
      DemCase many(yaml, {0, 0, -9.81});
      many->setThreadSpeeds(split.speeds);
      start(*many);
      for (int s = 0; s < steps; ++s) many->step(2e-5);
      std::string speeds;
      for (double v : split.speeds) speeds += std::to_string(v) + " ";
      EXPECT_EQ(snapshot(*many), reference)
          << (isLattice ? "lattice" : "bed") << ", " << split.team << " threads, speeds " << (speeds.empty() ? "measured" : speeds);
    }
  }
  setThreadCount(1);
}

// A skewed speed moves the force loop's split (the integration follows it), within its bounds.
TEST(DemSystem, ThreadSpeedsMoveTheSplit) {
  setThreadCount(2);
  DemCase bed(bedCase(2), {0, 0, -9.81});
  bed->step(2e-5);
  const std::vector<std::size_t> equal = bed->threadBlocks();
  ASSERT_EQ(equal.size(), 3u);
  bed->setThreadSpeeds({0.5, 2.0});
  bed->step(2e-5);
  const std::size_t n = bed->particles().size();
  // The first thread, a quarter as fast, gets about a fifth of the work: fewer rows than with equal
  // shares (the rows' costs differ: not exactly a fifth of the rows).
  const std::vector<std::size_t>& skewed = bed->forceLoopBlocks();
  ASSERT_EQ(skewed.size(), 3u);
  EXPECT_LT(skewed[1], equal[1]);
  EXPECT_GT(skewed[1], n / 10);
  EXPECT_LT(skewed[1], n / 3);
  setThreadCount(1);
}

TEST(DemSystem, RestartContinuesBitIdentically) {
  const std::string yaml = bedCase(1, "  rolling: epsd\n  rolling_friction: 0.1");
  DemCase continuous(yaml, {0, 0, -9.81});
  for (int s = 0; s < 700; ++s) continuous->step(2e-5);
  const std::vector<char> saved = snapshot(*continuous);
  for (int s = 0; s < 700; ++s) continuous->step(2e-5);

  DemCase restarted(yaml, {0, 0, -9.81});
  BinaryReader reader(saved.data(), saved.size());
  restarted->load(reader);
  EXPECT_TRUE(reader.atEnd());
  for (int s = 0; s < 700; ++s) restarted->step(2e-5);
  EXPECT_EQ(snapshot(*restarted), snapshot(*continuous));
}

// A system built for a restart inserts nothing (the case's random packing would be discarded), yet
// after load() it continues exactly like the uninterrupted run, on 1 and 2 threads, and the
// time-step check already knows the case's spheres before the load.
TEST(DemSystem, RestartIntoASystemBuiltWithoutInsertionContinuesBitIdentically) {
  for (int threads : {1, 2}) {
    setThreadCount(threads);
    const std::string yaml = bedCase(threads, "  rolling: epsd\n  rolling_friction: 0.1");
    DemCase continuous(yaml, {0, 0, -9.81});
    for (int s = 0; s < 500; ++s) continuous->step(2e-5);
    const std::vector<char> saved = snapshot(*continuous);
    for (int s = 0; s < 500; ++s) continuous->step(2e-5);

    DemCase restarted(yaml, {0, 0, -9.81}, InitialParticles::FromCheckpoint);
    EXPECT_EQ(restarted->particles().size(), 0u);
    EXPECT_TRUE(std::isfinite(restarted->rayleighTime()));
    EXPECT_LE(restarted->rayleighTime(), continuous->rayleighTime());
    BinaryReader reader(saved.data(), saved.size());
    restarted->load(reader);
    EXPECT_TRUE(reader.atEnd());
    EXPECT_EQ(restarted->particles().size(), continuous->particles().size());
    for (int s = 0; s < 500; ++s) restarted->step(2e-5);
    EXPECT_EQ(snapshot(*restarted), snapshot(*continuous)) << threads << " threads";
  }
  setThreadCount(1);
}

// External forces are sized on demand: a DEM-only system holds none (48 B per particle less);
// enabled with zero values they change nothing; once enabled they stay one per particle through
// insertion, removal, reordering and a restart, and an all-zero set is dropped at load.
TEST(DemSystem, ExternalForcesAreSizedOnDemandAndChangeNothingWhenZero) {
  const std::string yaml = bedCase(1, "");
  DemCase plain(yaml, {0, 0, -9.81});
  DemCase zeroed(yaml, {0, 0, -9.81});
  EXPECT_FALSE(plain->particles().hasExternalForces);
  EXPECT_TRUE(plain->particles().externalForce.empty());
  const std::size_t bytesWithout = plain->memoryBytes();
  zeroed->particles().enableExternalForces();
  const std::size_t n = zeroed->particles().size();
  ASSERT_EQ(zeroed->particles().externalForce.size(), n);
  EXPECT_GE(zeroed->memoryBytes(), bytesWithout + 2 * n * sizeof(Vec3));
  for (int s = 0; s < 700; ++s) {
    plain->step(2e-5);
    zeroed->step(2e-5);
  }
  EXPECT_EQ(plain->particles().position, zeroed->particles().position);
  EXPECT_EQ(plain->particles().velocity, zeroed->particles().velocity);

  // an external torque turns the particles it acts on only while hasExternalTorques says it is
  // there (false: the force loop does not read the torques, which are all zero then)
  {
    DemCase turned(yaml, {0, 0, -9.81});
    ParticleSet& q = turned->particles();
    q.enableExternalForces();
    EXPECT_TRUE(q.hasExternalTorques);
    for (Vec3& t : q.externalTorque) t = Vec3{0.0, 0.0, 1e-9};
    DemCase reference(yaml, {0, 0, -9.81});
    reference->particles().enableExternalForces();
    reference->particles().clearExternalTorques();
    turned->step(2e-5);
    reference->step(2e-5);
    double spin = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i)
      spin += q.angularVelocity[i].z - reference->particles().angularVelocity[i].z;
    EXPECT_GT(spin, 0.0);
    EXPECT_EQ(q.position, reference->particles().position);  // (a torque moves nothing in one step)
    q.clearExternalTorques();
    EXPECT_FALSE(q.hasExternalTorques);
    for (const Vec3& t : q.externalTorque) ASSERT_EQ(t, Vec3{});
    // a checkpoint with zero torques but non-zero forces: forces kept, torques flagged absent
    q.externalForce[0] = Vec3{1e-4, 0, 0};
    const std::vector<char> saved = snapshot(*turned);
    DemCase restarted(yaml, {0, 0, -9.81});
    BinaryReader reader(saved.data(), saved.size());
    restarted->load(reader);
    EXPECT_TRUE(restarted->particles().hasExternalForces);
    EXPECT_FALSE(restarted->particles().hasExternalTorques);
  }

  // a standalone set: the arrays stay one per particle through add and gather (reordering)
  ParticleSet loose = randomParticles(50, {0.01, 0.01, 0.01}, 3);
  loose.enableExternalForces();
  const std::size_t added = loose.add(999999, 0, 0.001, 2500, {0.003, 0.003, 0.015});
  ASSERT_EQ(loose.externalForce.size(), loose.size());
  loose.externalForce[added] = Vec3{1e-4, 0, 0};
  std::vector<std::uint32_t> reversed(loose.size());
  for (std::size_t k = 0; k < loose.size(); ++k) reversed[k] = static_cast<std::uint32_t>(loose.size() - 1 - k);
  loose.gather(reversed);
  ASSERT_EQ(loose.externalTorque.size(), loose.size());
  EXPECT_EQ(loose.id[0], 999999);
  EXPECT_EQ(loose.externalForce[0].x, 1e-4);

  // a restart keeps non-zero external forces
  ParticleSet& p = zeroed->particles();
  p.externalForce[0] = Vec3{1e-4, 0, 0};
  const std::vector<char> saved = snapshot(*zeroed);
  DemCase restarted(yaml, {0, 0, -9.81});
  BinaryReader reader(saved.data(), saved.size());
  restarted->load(reader);
  EXPECT_TRUE(restarted->particles().hasExternalForces);
  EXPECT_EQ(restarted->particles().externalForce, p.externalForce);

  // all zero at save: dropped at load, same state otherwise
  p.externalForce[0] = Vec3{};
  const std::vector<char> savedZero = snapshot(*zeroed);
  DemCase reloaded(yaml, {0, 0, -9.81});
  BinaryReader zeroReader(savedZero.data(), savedZero.size());
  reloaded->load(zeroReader);
  EXPECT_FALSE(reloaded->particles().hasExternalForces);
  EXPECT_TRUE(reloaded->particles().externalForce.empty());
  EXPECT_EQ(reloaded->particles().position, p.position);
}

// Elastic (e = 1), frictionless particles in a closed box: velocity Verlet conserves the total
// energy (kinetic + elastic Hertz potential 2/5 k d^(5/2)) to 0.1 % over 1e5 steps.
TEST(DemSystem, ElasticBoxConservesEnergy) {
  const std::string yaml = materialsYaml("hertz_mindlin", 1.0, 0.0) + R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
walls:
  - {type: box, min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
insertion:
  - {type: random_packing, min: [0, 0, 0], max: [0.01, 0.01, 0.01], count: 40, seed: 2,
     size: {diameter: 0.002}}
)";
  DemCase c(yaml, {0, 0, 0});
  Random rng(11);
  for (Vec3& v : c->particles().velocity) v = {rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5)};
  c->refresh();
  const double e0 = c->energy().total();
  double maxDeviation = 0.0;
  const double dt = 0.02 * c->rayleighTime();
  for (int s = 0; s < 100000; ++s) {
    c->step(dt);
    if (s % 100 == 0) maxDeviation = std::max(maxDeviation, std::abs(c->energy().total() - e0));
  }
  EXPECT_LT(maxDeviation, 1e-3 * e0);
  EXPECT_GT(c->contactStatistics().particleContacts + c->steps(), 0);
}

TEST(DemSystem, TimeStepCheckAgainstRayleighTime) {
  const double tR = rayleighTime(0.001, 2500, 1e7, 0.3);
  // t_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766), G = E / (2 (1 + nu)) (Li et al. 2005).
  EXPECT_NEAR(tR, std::numbers::pi * 0.001 * std::sqrt(2500 / (1e7 / 2.6)) / (0.1631 * 0.3 + 0.8766), 1e-15);
  EXPECT_EQ(checkTimeStep(0.1 * tR, tR).verdict, TimeStepVerdict::Ok);
  EXPECT_EQ(checkTimeStep(0.3 * tR, tR).verdict, TimeStepVerdict::Warning);
  EXPECT_EQ(checkTimeStep(0.6 * tR, tR).verdict, TimeStepVerdict::Error);
  EXPECT_NE(checkTimeStep(0.6 * tR, tR).message.find("Rayleigh"), std::string::npos);
}

TEST(DemSystem, HealthCheckNamesParticle) {
  DemCase c(materialsYaml("hertz_mindlin", 0.5, 0.5) + "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n", {0, 0, 0});
  c->particles().add(42, 0, 0.001, 2500, {0.5, 0.5, 0.5}, {0, 0, 100});
  c->refresh();
  for (int s = 0; s < 200; ++s) c->step(0.001);
  try {
    c->checkHealth(200, 0.2);
    FAIL() << "expected DivergenceError";
  } catch (const DivergenceError& e) {
    EXPECT_NE(std::string(e.what()).find("42"), std::string::npos);
  }
}

TEST(DemSystem, HealthCheckReportsTheFirstUnhealthyParticleOnAnyThreadCount) {
  // 2,000 particles (a team scans them on several threads): the lowest index is reported, the
  // domain exit of index 700 before the NaN of index 1500, then the NaN once 700 is back inside.
  DemCase c(materialsYaml("hertz_mindlin", 0.5, 0.5) + "domain: {min: [0, 0, 0], max: [1, 1, 1]}\n", {0, 0, 0});
  ParticleSet& p = c->particles();
  for (int i = 0; i < 2000; ++i) p.add(1000 + i, 0, 0.001, 2500, {0.1 + 0.0004 * i, 0.5, 0.5});
  p.velocity[1500].z = std::numeric_limits<double>::quiet_NaN();
  p.position[700].x = 1.5;
  const int threadsBefore = threadCount();
  auto report = [&] {
    try {
      c->checkHealth(7, 0.1);
    } catch (const DivergenceError& e) {
      return std::string(e.what());
    }
    return std::string("healthy");
  };
  for (int threads : {1, 2, 3}) {
    setThreadCount(threads);
    const std::string outside = report();
    EXPECT_NE(outside.find("left the domain"), std::string::npos) << outside;
    EXPECT_NE(outside.find("particle id 1700"), std::string::npos) << outside;
    p.position[700].x = 0.5;
    const std::string nan = report();
    EXPECT_NE(nan.find("NaN"), std::string::npos) << nan;
    EXPECT_NE(nan.find("particle id 2500"), std::string::npos) << nan;
    p.velocity[1500].z = 0.0;
    EXPECT_EQ(report(), "healthy");
    p.velocity[1500].z = std::numeric_limits<double>::quiet_NaN();
    p.position[700].x = 1.5;
  }
  setThreadCount(threadsBefore);
}

}  // namespace
}  // namespace gf::dem
