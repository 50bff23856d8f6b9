// The direct forcing on the MAC faces (src/resolved/forcing.hpp) and the fictitious-domain step
// (src/resolved/fictitious_domain.hpp) with the fluid solver: the forcing's force is the momentum it
// removes, a rigid motion already present costs nothing, and the drag on a cylinder does not jump
// when the cylinder moves by a tenth of a cell.
#include "resolved/forcing.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/domain.hpp"
#include "dem/particles.hpp"
#include "fluid/solver.hpp"
#include "resolved/fictitious_domain.hpp"

namespace gf::resolved {
namespace {

constexpr double kPi = std::numbers::pi;

FaceBox cubeBox(int n, double h) {
  FaceBox box;
  box.grid.origin = Vec3{0, 0, 0};
  box.grid.spacing = Vec3{h, h, h};
  box.grid.cells = {n, n, n};
  box.global = {n, n, n};
  return box;
}

void fillFaces(Field (&u)[3], const FaceBox& box, const std::function<Vec3(const Vec3&)>& f) {
  for (int c = 0; c < 3; ++c) {
    u[c] = Field(box.grid, static_cast<Staggering>(c + 1));
    const auto& pts = u[c].points();
    for (int k = 0; k < pts[2]; ++k)
      for (int j = 0; j < pts[1]; ++j)
        for (int i = 0; i < pts[0]; ++i) {
          const int idx[3] = {i, j, k};
          Vec3 x;
          for (int a = 0; a < 3; ++a) x[a] = box.grid.origin[a] + (idx[a] + (a == c ? 0.0 : 0.5)) * box.grid.spacing[a];
          u[c](i, j, k) = f(x)[c];
        }
  }
}

TEST(Forcing, StoppingAUniformStreamGivesTheSphereItsMomentum) {
  // u = (1, 0, 0) everywhere, a fixed sphere (R = 4 cells): the forcing brings the covered part of
  // each face to rest. Its force on the body is rho gamma0 / dt times the momentum removed, sum phi
  // V = the sphere's volume (the faces' control volumes tile space), to the kernel's 1e-9.
  const FaceBox box = cubeBox(16, 0.5);
  Field u[3];
  fillFaces(u, box, [](const Vec3&) { return Vec3{1.0, 0.0, 0.0}; });
  Body b;
  b.centre = Vec3{4.03, 3.91, 4.17};
  b.radius = 2.0;
  const double rho = 2.0, gamma0 = 1.5, dt = 0.1, V = 4.0 / 3.0 * kPi * 8.0;
  const FaceSums s = imposeRigidMotion(b, box, u, rho, gamma0, dt);
  EXPECT_NEAR(s.force.x, rho * gamma0 / dt * V, 1e-8 * rho * gamma0 / dt * V);
  EXPECT_NEAR(s.force.y, 0.0, 1e-12);
  EXPECT_NEAR(s.force.z, 0.0, 1e-12);
  // (torque about the centre: the face points are not the centroids of the covered parts; small)
  EXPECT_LT(norm(s.torque), 0.02 * s.force.x * b.radius);
  // A face deep inside is at rest, one far away untouched.
  EXPECT_DOUBLE_EQ(u[0](8, 7, 8), 0.0);
  EXPECT_DOUBLE_EQ(u[0](1, 1, 1), 1.0);
  // The fluid momentum inside is now zero (to the partly covered faces' remaining share: small).
  const FaceSums inside = fluidMomentumInside(b, box, {&u[0], &u[1], &u[2]});
  EXPECT_LT(std::abs(inside.momentum.x), 0.15 * V);
}

TEST(Forcing, ARigidMotionAlreadyPresentNeedsNoForce) {
  // The fluid already moves as the body would (translation + rotation): no force, no torque, the
  // faces unchanged.
  const FaceBox box = cubeBox(12, 1.0);
  Body b;
  b.centre = Vec3{6.2, 5.7, 6.05};
  b.radius = 3.0;
  b.velocity = Vec3{0.3, -0.1, 0.2};
  b.angularVelocity = Vec3{0.5, -1.0, 2.0};
  Field u[3];
  fillFaces(u, box, [&](const Vec3& x) { return rigidVelocity(b, x); });
  const Field before = u[1];
  const FaceSums s = imposeRigidMotion(b, box, u, 1.0, 1.0, 0.01);
  EXPECT_LT(norm(s.force), 1e-9);
  EXPECT_LT(norm(s.torque), 1e-9);
  EXPECT_EQ(u[1].data(), before.data());
  // Its fluid momentum inside is the body's: V U (to the rotation sampled at face points, not at the
  // centroids of the covered parts: 1 %), and the angular part I omega / rho, I / rho = 2/5 V R^2, to
  // the face sampling of the second moment, of relative size (h / R)^2 / 2.4 (4.6 % at R = 3 h): 6 %.
  const FaceSums in = fluidMomentumInside(b, box, {&u[0], &u[1], &u[2]});
  const double V = 4.0 / 3.0 * kPi * 27.0;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(in.momentum[a], V * b.velocity[a], 0.01 * V * norm(b.angularVelocity) * 3.0) << a;
  const double inertia = 0.4 * V * 9.0;
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(in.angularMomentum[a], inertia * b.angularVelocity[a], 0.06 * inertia * norm(b.angularVelocity)) << a;
}

/// Drag on a fixed cylinder (D = 8 cells) in a channel at Re = 20 after a fixed time, the cylinder
/// shifted by `shift` cells along x and y.
double cylinderDrag(double shift) {
  const double c = 1.0 + shift * 0.0625;
  const std::string text = fmt::format(R"(
domain: {{min: [0, 0, 0], max: [4.0, 2.0, 0.0625]}}
fluid:
  density: 1.0
  viscosity: 0.05
  cells: [64, 32, 1]
  boundaries:
    x_min: {{type: inlet, velocity: [1.0, 0.0, 0.0]}}
    x_max: {{type: pressure_outlet}}
    y_min: {{type: slip}}
    y_max: {{type: slip}}
resolved:
  bodies:
    - {{shape: cylinder, centre: [{}, {}, 0.0], radius: 0.25}}
)",
                                       c, c);
  Params root = Params::loadString(text, "cylinder.yaml");
  const Domain domain = Domain::read(root);
  fluid::Solver fluid(root, domain, Vec3{});
  fluid.setVelocity([](const Vec3&) { return Vec3{1.0, 0.0, 0.0}; });
  dem::ParticleSet particles;
  FictitiousDomain fd(root, fluid, particles, domain, Vec3{});
  for (int n = 0; n < 120; ++n) fd.fluidStep(fluid, particles, 0.02);
  return fd.fixedBodies()[0].load.force.x / (0.5 * 1.0 * 1.0 * 0.5 * 0.0625);  // Cd
}

TEST(FictitiousDomain, CylinderDragDoesNotJumpWhenTheCylinderMovesByATenthOfACell) {
  // Re = U D / nu = 10, 8 cells per diameter, the same time (4.8 D / U) for every shift of 0, 0.1,
  // ..., 0.5 cells along the diagonal. The drag coefficient drifts smoothly with the sub-cell position
  // (the forcing's effective diameter depends on where the surface cuts the cells: a few per cent over
  // half a cell at this resolution), by less than 1.5 % per tenth of a cell, with increments that
  // change by less than 1 % of Cd from one tenth to the next: no jump. A stair-step body would change
  // its cells, and its drag, at once.
  std::vector<double> cd;
  for (int s = 0; s <= 5; ++s) cd.push_back(cylinderDrag(0.1 * s));
  for (std::size_t s = 0; s < cd.size(); ++s) {
    ASSERT_TRUE(std::isfinite(cd[s]));
    EXPECT_GT(cd[s], 3.0);
    EXPECT_LT(cd[s], 6.0);
    if (s > 0) {
      EXPECT_LT(std::abs(cd[s] - cd[s - 1]), 0.015 * cd[0]) << s;
    }
    if (s > 1) {
      EXPECT_LT(std::abs((cd[s] - cd[s - 1]) - (cd[s - 1] - cd[s - 2])), 0.01 * cd[0]) << s;
    }
  }
  std::printf("Cd at shifts 0, 0.1, ..., 0.5 cells: %.4f %.4f %.4f %.4f %.4f %.4f\n", cd[0], cd[1], cd[2], cd[3], cd[4],
              cd[5]);
}

}  // namespace
}  // namespace gf::resolved
