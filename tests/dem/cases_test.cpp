// Every cases/dem_*.yaml is loaded through the System API and run shortened; the hopper case is
// run long enough to check its discharge rate against Beverloo's correlation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/monitor.hpp"
#include "dem/system.hpp"

namespace gf::dem {
namespace {

const std::filesystem::path kCases = std::filesystem::path(GRAINFLOW_SOURCE_DIR) / "cases";

struct LoadedCase {
  Params root;
  Domain domain;
  double dt = 0.0;
  std::unique_ptr<System> system;
  std::vector<std::unique_ptr<Monitor>> monitors;
  explicit LoadedCase(const std::string& name) : root(Params::loadFile((kCases / name).string())) {
    domain = Domain::read(root);
    const Vec3 gravity = root.vec3({"gravity", "m/s^2", "gravity"}, {0, 0, -9.81});
    Params time = root.section({"time", "-", "time stepping"});
    dt = time.real({"dem_step", "s", "DEM time step", Range::positive()});
    system = std::make_unique<System>(root, domain, gravity);
    for (Params& m : root.list({"monitors", "-", "monitors"}))
      monitors.push_back(Registry<Monitor>::instance().create(m, {"type", "-", "monitor"}));
  }
};

class DemCaseFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(DemCaseFiles, RunsShortenedWithValidTimeStepAndMonitors) {
  LoadedCase c(GetParam());
  System& s = *c.system;
  EXPECT_GT(s.particles().size(), 500u);
  EXPECT_NE(s.checkTimeStep(c.dt).verdict, TimeStepVerdict::Error) << s.checkTimeStep(c.dt).message;
  const double e0 = s.energy().total();
  for (int k = 0; k < 300; ++k) s.step(c.dt);
  EXPECT_NO_THROW(s.checkHealth(300, s.time()));
  EXPECT_LE(s.energy().total(), e0 * (1.0 + 1e-9));  // dissipative contacts: never gains energy
  const RunState state{s.time(), s.steps(), &s, nullptr, nullptr, {}};
  for (auto& m : c.monitors) {
    const std::vector<double> values = m->sample(state);
    EXPECT_EQ(values.size(), m->columns().size());
    for (double v : values) EXPECT_TRUE(std::isfinite(v));
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, DemCaseFiles,
                         ::testing::Values("dem_packed_bed_settling.yaml", "dem_hopper_discharge.yaml",
                                           "dem_rotating_drum.yaml"));

// Beverloo, Leniger & van de Velde (1961): W = C rho_b sqrt(g) (D - k d)^(5/2) with C = 0.58,
// k = 1.5 (Nedderman 1992, Statics and kinematics of granular materials, ch. 10). The measured
// steady discharge rate must be within 15 %.
TEST(DemCases, HopperDischargeMatchesBeverlooWithinFifteenPercent) {
  LoadedCase c("dem_hopper_discharge.yaml");
  System& s = *c.system;
  const double d = 0.003, orifice = 0.021, siloRadius = 0.03, rho = 2500.0, g = 9.81;
  while (s.time() < 0.29) s.step(c.dt);
  // Bulk density of the settled bed from a slab well inside it.
  double solid = 0.0, top = 0.0;
  for (std::size_t i = 0; i < s.particles().size(); ++i) top = std::max(top, s.particles().position[i].z);
  const double z0 = 0.004, z1 = top - 0.008;  // away from the floor and the rough surface
  ASSERT_GT(z1, z0 + 0.008) << "bed too low: top " << top;
  for (std::size_t i = 0; i < s.particles().size(); ++i) {
    const double z = s.particles().position[i].z, r = s.particles().radius[i];
    if (z > z0 && z < z1) solid += 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  const double bulkDensity = rho * solid / (std::numbers::pi * siloRadius * siloRadius * (z1 - z0));
  const double beverloo = 0.58 * bulkDensity * std::sqrt(g) * std::pow(orifice - 1.5 * d, 2.5);
  // Steady discharge (plug gone at 0.3 s, fall to the bin about 0.08 s): 0.42 s to 0.62 s.
  while (s.time() < 0.42) s.step(c.dt);
  const double m0 = s.outlets()[0].removedMass;
  while (s.time() < 0.62) s.step(c.dt);
  const double rate = (s.outlets()[0].removedMass - m0) / 0.2;
  std::printf("[ hopper ] bulk density %.0f kg/m^3, discharge %.4f kg/s, Beverloo (C=0.58, k=1.5) %.4f kg/s\n",
              bulkDensity, rate, beverloo);
  EXPECT_NEAR(rate, beverloo, 0.15 * beverloo);
}

}  // namespace
}  // namespace gf::dem
