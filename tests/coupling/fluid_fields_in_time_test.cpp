// FluidFieldsInTime: the fluid between two fluid steps as the DEM substeps see it
// (substep_fluid_fields: interpolated).
#include <gtest/gtest.h>

#include "coupling/fluid_fields_in_time.hpp"
#include "coupling_test_helpers.hpp"

using namespace gf;
using namespace gf::coupling;
using namespace gf::coupling::testing;

TEST(FluidFieldsInTime, BlendsLinearlyAndGivesTheNewViewItselfAtTheEnd) {
  const CartesianGrid g = makeGrid({3, 2, 4}, {0.01, 0.01, 0.01});
  FluidFields before(g), after(g);
  before.setVelocity(g, [](const Vec3& x) { return Vec3{1.0 + x.x, -2.0, 3.0 * x.z}; });
  before.setPressureGradient(g, [](const Vec3&) { return Vec3{0.0, 0.0, -100.0}; });
  after.setVelocity(g, [](const Vec3& x) { return Vec3{5.0 - x.y, 2.0, 0.0}; });
  after.setPressureGradient(g, [](const Vec3&) { return Vec3{10.0, 0.0, -300.0}; });
  const FluidView end = after.view(1.2, 1.8e-5, 1e-3);

  FluidFieldsInTime inTime;
  // no start kept yet: the new view (with the substep's time step)
  FluidView v = inTime.at(end, 0.3, 1e-4);
  EXPECT_EQ(v.velocity[0], end.velocity[0]);
  EXPECT_EQ(v.timeStep, 1e-4);

  inTime.keepStart(before.view(1.2, 1.8e-5, 1e-3));
  before.setVelocity(g, [](const Vec3&) { return Vec3{99.0, 99.0, 99.0}; });  // (kept as a copy)
  for (double theta : {0.1, 0.5, 0.9}) {
    v = inTime.at(end, theta, 1e-4);
    EXPECT_EQ(v.density, 1.2);
    EXPECT_EQ(v.viscosity, 1.8e-5);
    EXPECT_EQ(v.viscousStressDivergence[0], nullptr);
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
          const Vec3 x = g.cellCentre(i, j, k);
          const Vec3 u0{1.0 + x.x, -2.0, 3.0 * x.z}, u1{5.0 - x.y, 2.0, 0.0};
          for (int a = 0; a < 3; ++a) EXPECT_NEAR((*v.velocity[a])(i, j, k), (1 - theta) * u0[a] + theta * u1[a], 1e-14);
          EXPECT_NEAR((*v.pressureGradient[0])(i, j, k), theta * 10.0, 1e-12);
          EXPECT_NEAR((*v.pressureGradient[2])(i, j, k), -100.0 - theta * 200.0, 1e-12);
        }
  }
  v = inTime.at(end, 1.0, 1e-4);  // the last substep: the new fields themselves
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(v.velocity[a], end.velocity[a]);
    EXPECT_EQ(v.pressureGradient[a], end.pressureGradient[a]);
  }
}
