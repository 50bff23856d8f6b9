// Monitor fluid_line_profile (src/fluid/monitors/line_profile_monitor.cpp, sampling lineProfile):
// one row per cell along the line, against fields whose sampled values are known exactly.
//  - Taylor-Green vortex (Taylor & Green 1937) on the staggered faces: the cell-centred velocity is
//    the mean of the two faces, u(x - h/2) + u(x + h/2) = 2 u(x) cos(k h / 2) for a sine of
//    wavenumber k, so on a line through cell centres the profile is the field times cos(k h / 2).
//  - A linear field off the cell centres: the face mean and the linear interpolation between the
//    centres are both exact.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "core/monitor.hpp"
#include "fluid/initial_condition.hpp"
#include "fluid/sampling.hpp"
#include "fluid_test_util.hpp"

namespace gf::fluid {
namespace {

std::unique_ptr<Monitor> lineMonitor(const std::string& yaml) {
  Params p = Params::loadString(yaml, "monitor.yaml");
  return Registry<Monitor>::instance().createByName("fluid_line_profile", p);
}

RunState stateOf(const Solver& s) {
  RunState st;
  st.time = 2.5;
  st.fluid = &s;
  return st;
}

TEST(LineProfile, TaylorGreenAlongTheVerticalLineThroughCellCentres) {
  // Wavelength 2 m in a 2 m periodic box, U0 = 0.5 m/s, plus a uniform 0.1 m/s along x; 16 x 16 x 2 cells.
  auto c = test::makeCase(
      "domain: {min: [0, 0, 0], max: [2, 2, 0.5], periodic: [1, 1, 1]}\n"
      "fluid:\n  density: 3.0\n  cells: [16, 16, 2]\n"
      "  initial: {type: taylor_green, amplitude: 0.5, wavelength: 2.0, velocity: [0.1, 0, 0], pressure: 7.0}\n");
  const Solver& s = *c.solver;
  const double k = std::numbers::pi, h = 2.0 / 16, u0 = 0.5;
  const Vec3 centre = s.grid().cellCentre(5, 0, 1);  // x = 0.6875, z = 0.375: on cell centres
  auto monitor = lineMonitor(fmt::format("{{line_axis: y, line_point: [{}, 0.3, {}]}}", centre.x, centre.z));
  const auto columns = monitor->columns();
  ASSERT_EQ(columns.size(), 6u);
  EXPECT_EQ(columns[0].name, "y");
  EXPECT_EQ(columns[0].unit, "m");
  EXPECT_EQ(columns[1].name, "velocity_x");
  EXPECT_EQ(columns[4].name, "pressure");
  EXPECT_EQ(columns[5].name, "void_fraction");

  const auto rows = monitor->sampleRows(stateOf(s));
  ASSERT_EQ(rows.size(), 16u);  // every cell along y
  for (int j = 0; j < 16; ++j) {
    const auto& r = rows[j];
    ASSERT_EQ(r.size(), columns.size());
    const double y = (j + 0.5) * h;
    EXPECT_NEAR(r[0], y, 1e-14);
    EXPECT_NEAR(r[1], 0.1 + u0 * std::sin(k * centre.x) * std::cos(k * y) * std::cos(k * h / 2), 1e-13) << "j = " << j;
    EXPECT_NEAR(r[2], -u0 * std::cos(k * centre.x) * std::sin(k * y) * std::cos(k * h / 2), 1e-13) << "j = " << j;
    EXPECT_NEAR(r[3], 0.0, 1e-14);
    EXPECT_NEAR(r[4], 7.0 + taylorGreenPressure({centre.x, y, centre.z}, u0, k, 3.0), 1e-13) << "j = " << j;
    EXPECT_DOUBLE_EQ(r[5], 1.0);
  }
  EXPECT_EQ(monitor->sample(stateOf(s)), rows.front());
}

TEST(LineProfile, LinearFieldBetweenTheCellCentres) {
  auto c = test::makeCase("domain: {min: [0, 0, 0], max: [1, 1, 1], periodic: [1, 1, 1]}\nfluid:\n  cells: [8, 8, 8]\n");
  Solver& s = *c.solver;
  // u varies across the line only (periodic along x); p linear in all three directions.
  s.setVelocity([](const Vec3& x) { return Vec3{0.2 + 0.3 * x.y + 0.7 * x.z, 0.0, 0.0}; });
  s.setPressure([](const Vec3& x) { return 1.0 + 2.0 * x.x + 3.0 * x.y + 4.0 * x.z; });
  const LineProfile line = lineProfile(s, 0, {0.5, 0.37, 0.61});
  ASSERT_EQ(line.position.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) {
    const double x = (static_cast<double>(i) + 0.5) / 8.0;
    EXPECT_NEAR(line.position[i], x, 1e-15);
    EXPECT_NEAR(line.velocity[i][0], 0.2 + 0.3 * 0.37 + 0.7 * 0.61, 1e-14);
    EXPECT_NEAR(line.pressure[i], 1.0 + 2.0 * x + 3.0 * 0.37 + 4.0 * 0.61, 1e-13);
  }
}

TEST(LineProfile, NeedsAnAxisAndWritesNoRowsWithoutAFluid) {
  EXPECT_THROW(lineMonitor("{line_point: [0, 0, 0]}"), CaseError);
  EXPECT_THROW(lineMonitor("{line_axis: w, line_point: [0, 0, 0]}"), CaseError);
  auto monitor = lineMonitor("{line_axis: z, line_point: [0, 0, 0]}");
  EXPECT_EQ(monitor->columns().front().name, "z");
  EXPECT_TRUE(monitor->sampleRows(RunState{}).empty());
  for (double v : monitor->sample(RunState{})) EXPECT_TRUE(std::isnan(v));
}

}  // namespace
}  // namespace gf::fluid
