// mass_flow monitor: counts the mass crossing a plane, and a restart from a checkpoint (DEM state +
// monitor state) writes the same samples as the uninterrupted run.
#include <gtest/gtest.h>

#include <numbers>

#include "core/monitor.hpp"
#include "dem_test_util.hpp"

namespace gf::dem::test {
namespace {

// 4 x 4 x 6 spheres falling (no contacts: spacing 3 d) through the plane z = 0.03.
const std::string kFalling = materialsYaml("hertz_mindlin", 0.5, 0.5) + R"(
domain: {min: [0, 0, -0.1], max: [0.03, 0.03, 0.1]}
insertion:
  - {type: lattice, origin: [0.005, 0.005, 0.031], spacing: 0.006, nx: 4, ny: 4, nz: 6, diameter: 0.002,
     velocity: [0, 0, -3]}
)";

std::unique_ptr<Monitor> massFlowMonitor(Params&) {
  Params p = Params::loadString("{type: mass_flow, point: [0, 0, 0.03], normal: [0, 0, -1]}\n", "monitor.yaml");
  return Registry<Monitor>::instance().create(p, {"type"});
}

std::vector<double> sampleAt(Monitor& m, const System& s) { return m.sample(RunState{s.time(), s.steps(), &s, nullptr, nullptr, {}}); }

constexpr double kDt = 1e-5;
constexpr int kStepsPerSample = 200;

}  // namespace

TEST(DemMassFlowMonitor, CountsAllParticlesThatCrossed) {
  DemCase c(kFalling, {0, 0, 0});
  auto m = massFlowMonitor(c.params);
  sampleAt(*m, *c);
  for (int k = 0; k < 400; ++k) c->step(kDt);  // 12 mm: the rows at 31 and 37 mm cross z = 30 mm
  const std::vector<double> v = sampleAt(*m, *c);
  const double particleMass = 2500.0 * std::numbers::pi / 6.0 * 8e-9;
  int crossed = 0;
  for (const Vec3& x : c->particles().position) crossed += x.z < 0.03;
  EXPECT_GT(crossed, 0);
  EXPECT_NEAR(v[0], crossed * particleMass, 1e-12);
}

TEST(DemMassFlowMonitor, RestartWritesTheSameSamplesAsContinuous) {
  // Continuous run: 8 samples.
  DemCase continuous(kFalling, {0, 0, -9.81});
  auto mc = massFlowMonitor(continuous.params);
  std::vector<std::vector<double>> expected{sampleAt(*mc, *continuous)};
  for (int s = 0; s < 8; ++s) {
    for (int k = 0; k < kStepsPerSample; ++k) continuous->step(kDt);
    expected.push_back(sampleAt(*mc, *continuous));
  }
  EXPECT_GT(expected.back()[0], 0.0);
  // Split run: checkpoint after 3 samples (6 ms: three rows crossed, the fourth crosses at 6.3 ms).
  DemCase first(kFalling, {0, 0, -9.81});
  auto m1 = massFlowMonitor(first.params);
  sampleAt(*m1, *first);
  for (int s = 0; s < 3; ++s) {
    for (int k = 0; k < kStepsPerSample; ++k) first->step(kDt);
    sampleAt(*m1, *first);
  }
  BinaryWriter out;
  first->save(out);
  m1->save(out);
  DemCase resumed(kFalling, {0, 0, -9.81});
  auto m2 = massFlowMonitor(resumed.params);
  BinaryReader in(out.bytes().data(), out.bytes().size());
  resumed->load(in);
  m2->load(in);
  EXPECT_TRUE(in.atEnd());
  for (int s = 3; s < 8; ++s) {
    for (int k = 0; k < kStepsPerSample; ++k) resumed->step(kDt);
    const std::vector<double> v = sampleAt(*m2, *resumed);
    ASSERT_EQ(v.size(), expected[s + 1].size());
    for (std::size_t q = 0; q < v.size(); ++q) EXPECT_EQ(v[q], expected[s + 1][q]) << "sample " << s + 1;
  }
  // Without the monitor's state the resumed run would count differently (the test can fail).
  DemCase blank(kFalling, {0, 0, -9.81});
  auto m3 = massFlowMonitor(blank.params);
  BinaryReader again(out.bytes().data(), out.bytes().size());
  blank->load(again);
  for (int k = 0; k < kStepsPerSample; ++k) blank->step(kDt);
  EXPECT_NE(sampleAt(*m3, *blank)[0], expected[4][0]);
}

}  // namespace gf::dem::test
