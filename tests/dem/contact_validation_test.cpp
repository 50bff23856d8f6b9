// Single-contact validation against analytic results: normal restitution, contact duration,
// oblique impact, sphere on an incline, rolling resistance.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "dem/contact/hertz_mindlin.hpp"
#include "dem/contact/hooke.hpp"
#include "dem/contact/restitution_damping.hpp"
#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

/// True unless every component is +0.0 bit for bit.
bool anyBitSet(const Vec3& v) {
  return std::bit_cast<std::uint64_t>(v.x) != 0 || std::bit_cast<std::uint64_t>(v.y) != 0 ||
         std::bit_cast<std::uint64_t>(v.z) != 0;
}

using test::DemCase;
using test::materialsYaml;

constexpr double kRadius = 0.001, kDensity = 2500.0;
const double kMass = kDensity * 4.0 / 3.0 * std::numbers::pi * kRadius * kRadius * kRadius;

std::string wallCase(const std::string& law, double e, double mu, double kHooke = 1e4) {
  return materialsYaml(law, e, mu, 1e7, 0.3, law == "hooke" ? fmt::format("  normal_stiffness: {}", kHooke) : "") + R"(
domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
)";
}

struct ImpactResult {
  Vec3 velocity, angularVelocity;
  double duration;
};

/// A sphere hits the plane z = 0 with velocity v (no gravity); returns the state after contact.
ImpactResult wallImpact(const std::string& yaml, const Vec3& v, double dt, const Vec3& omega = {}) {
  DemCase c(yaml, {0, 0, 0});
  c->particles().add(0, 0, kRadius, kDensity, {0, 0, kRadius + 1e-6}, v, omega);
  c->refresh();
  int contactSteps = 0;
  for (int s = 0; s < 2000000; ++s) {
    c->step(dt);
    const double z = c->particles().position[0].z;
    if (z < kRadius) ++contactSteps;
    else if (contactSteps > 0) break;
  }
  return {c->particles().velocity[0], c->particles().angularVelocity[0], contactSteps * dt};
}

double hertzWallDuration(double v) {
  const double eStar = 1e7 / (2.0 * (1.0 - 0.09));
  return hertz::elasticContactDuration(kMass, eStar, kRadius, v);
}

TEST(DemContact, DampingForRestitutionInvertsTheCollision) {
  for (double e : {0.1, 0.5, 0.9}) {
    EXPECT_NEAR(restitutionForDamping(dampingForRestitution(e, 1.5, 0.25), 1.5, 0.25), e, 1e-6);
    EXPECT_NEAR(restitutionForDamping(dampingForRestitution(e, 1.0, 0.0), 1.0, 0.0), e, 1e-6);
  }
  // Unclamped linear oscillator: e = exp(-pi zeta/sqrt(1-zeta^2)); with the no-tension clamp the
  // damping must be larger than that closed form gives (the clamp shortens the contact).
  const double e = 0.5, lnE = std::log(e);
  const double alphaClosedForm = -2.0 * lnE / std::sqrt(std::numbers::pi * std::numbers::pi + lnE * lnE);
  EXPECT_GT(dampingForRestitution(e, 1.0, 0.0), alphaClosedForm);
}

/// Two equal spheres approach head-on at v each (no gravity); contact duration (steps while the
/// centres are closer than 2 r) and relative velocity after.
ImpactResult pairImpact(const std::string& law, double e, double v, double dt) {
  DemCase c(materialsYaml(law, e, 0.5, 1e7, 0.3, law == "hooke" ? "  normal_stiffness: 1e4" : "") +
                "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\n",
            {0, 0, 0});
  c->particles().add(0, 0, kRadius, kDensity, {-kRadius - 1e-7, 0, 0}, {v, 0, 0});
  c->particles().add(1, 0, kRadius, kDensity, {kRadius + 1e-7, 0, 0}, {-v, 0, 0});
  c->refresh();
  int contactSteps = 0;
  for (int s = 0; s < 2000000; ++s) {
    c->step(dt);
    const auto& x = c->particles().position;
    if (x[1].x - x[0].x < 2.0 * kRadius) ++contactSteps;
    else if (contactSteps > 0) break;
  }
  const auto& u = c->particles().velocity;
  return {u[1] - u[0], {}, contactSteps * dt};
}

class RestitutionTest : public ::testing::TestWithParam<std::tuple<std::string, double>> {};

TEST_P(RestitutionTest, WallImpactRestitutionWithinOnePercent) {
  const auto& [law, e] = GetParam();
  const double v = 0.5;
  const double tc = law == "hooke" ? std::numbers::pi * std::sqrt(kMass / 1e4) : hertzWallDuration(v);
  const ImpactResult r = wallImpact(wallCase(law, e, 0.5), {0, 0, -v}, tc / 1000.0);
  EXPECT_NEAR(r.velocity.z / v, e, 0.01 * e) << law << " e=" << e;
}

TEST_P(RestitutionTest, ParticlePairRestitutionWithinOnePercent) {
  const auto& [law, e] = GetParam();
  const double v = 0.4;  // each, head-on
  const double eStar = 1e7 / (2.0 * (1.0 - 0.09));
  const double tc = law == "hooke" ? std::numbers::pi * std::sqrt(0.5 * kMass / 1e4)
                                   : hertz::elasticContactDuration(0.5 * kMass, eStar, 0.5 * kRadius, 2 * v);
  const ImpactResult r = pairImpact(law, e, v, tc / 300.0);
  EXPECT_NEAR(r.velocity.x / (2 * v), e, 0.01 * e) << law << " e=" << e;
}

INSTANTIATE_TEST_SUITE_P(Laws, RestitutionTest,
                         ::testing::Combine(::testing::Values("hertz_mindlin", "hooke"),
                                            ::testing::Values(0.1, 0.3, 0.5, 0.7, 0.9, 0.95)));

TEST(DemContact, HertzContactDurationWithinTwoPercent) {
  for (double v : {0.1, 1.0}) {
    const double tc = hertzWallDuration(v);  // Johnson 1985 eq. 11.24, elastic
    const ImpactResult r = wallImpact(wallCase("hertz_mindlin", 1.0, 0.5), {0, 0, -v}, tc / 500.0);
    EXPECT_NEAR(r.duration, tc, 0.02 * tc) << "v=" << v;
    EXPECT_NEAR(r.velocity.z, v, 1e-3 * v);  // elastic
  }
}

// Between two spheres (effective mass m/2, effective radius r/2): Hertz duration (Johnson 1985
// eq. 11.24) and the damped linear-spring duration pi / omega_d, within 2 %. Measured:
// Hertz within 1e-5; Hooke e = 1 within 1e-5, e = 0.5 0.8 % short (the normal force is not allowed
// to pull: it is clipped to zero once the dashpot outweighs the spring, before the overlap ends).
TEST(DemContact, ParticlePairContactDurationWithinTwoPercent) {
  const double eStar = 1e7 / (2.0 * (1.0 - 0.09)), mStar = 0.5 * kMass;
  for (double v : {0.05, 0.5}) {  // each: closing speed 2 v
    const double tc = hertz::elasticContactDuration(mStar, eStar, 0.5 * kRadius, 2.0 * v);
    const ImpactResult r = pairImpact("hertz_mindlin", 1.0, v, tc / 500.0);
    EXPECT_NEAR(r.duration, tc, 0.02 * tc) << "hertz v=" << v;
    EXPECT_NEAR(r.velocity.x, 2.0 * v, 1e-3 * v) << "elastic: the closing speed comes back";
  }
  for (double e : {1.0, 0.5}) {
    const double gamma = hooke::dampingCoefficient(dampingForRestitution(e, 1.0, 0.0), 1e4, mStar);
    const double tc = hooke::contactDuration(1e4, mStar, gamma);
    const ImpactResult r = pairImpact("hooke", e, 0.2, tc / 500.0);
    EXPECT_NEAR(r.duration, tc, 0.02 * tc) << "hooke e=" << e;
  }
}

TEST(DemContact, HookeContactDurationWithinTwoPercent) {
  for (double e : {1.0, 0.9}) {
    const double alpha = dampingForRestitution(e, 1.0, 0.0);
    const double gamma = hooke::dampingCoefficient(alpha, 1e4, kMass);
    const double tc = hooke::contactDuration(1e4, kMass, gamma);  // pi / omega_d
    const ImpactResult r = wallImpact(wallCase("hooke", e, 0.5), {0, 0, -0.3}, tc / 500.0);
    EXPECT_NEAR(r.duration, tc, 0.02 * tc) << "e=" << e;
  }
}

// Oblique impact of a sphere on a wall (Maw, Barber & Fawcett 1976; Thornton et al. 2013,
// Powder Technol. 233:30). Gross sliding when the incidence is steep enough: the tangential
// impulse is mu (1 + e) m v_n, so v_t' = v_t - mu (1 + e) v_n and w' R = 2.5 mu (1 + e) v_n
// (solid sphere, I = 2/5 m R^2). e = 0.95: the Tsuji damping force at first touch gives a short
// sticking phase whose impulse deficit grows with the damping (3 % at e = 0.7).
TEST(DemContact, ObliqueImpactGrossSlidingMatchesCoulombImpulse) {
  const double e = 0.95, mu = 0.2, vn = 0.3, vt = 1.0;
  for (const std::string law : {"hertz_mindlin", "hooke"}) {
    const double tc = law == "hooke" ? std::numbers::pi * std::sqrt(kMass / 1e4) : hertzWallDuration(vn);
    const ImpactResult r = wallImpact(wallCase(law, e, mu), {vt, 0, -vn}, tc / 400.0);
    const double expectedVt = vt - mu * (1 + e) * vn;
    EXPECT_NEAR(r.velocity.x, expectedVt, 0.02 * expectedVt) << law;
    EXPECT_NEAR(r.velocity.z, e * vn, 0.01 * e * vn) << law;
    // Friction along -x at the contact point -R z gives a spin about +y.
    const double expectedSpin = 2.5 * mu * (1 + e) * vn / kRadius;
    EXPECT_NEAR(r.angularVelocity.y, expectedSpin, 0.02 * expectedSpin) << law;
  }
}

// Small incidence angle (psi_1 = v_t/(mu v_n) << 1, Maw et al. 1976): the contact sticks, the
// tangential impulse stays below mu J_n and the elastic tangential spring returns part of the
// tangential surface velocity (|psi_2| < psi_1), unlike gross sliding where the change of the
// contact-point velocity is exactly 3.5 mu (1 + e) v_n.
TEST(DemContact, ObliqueImpactStickingReversesContactPointVelocity) {
  const double e = 0.9, mu = 0.5, vn = 0.3, vt = 0.02;
  const double tc = hertzWallDuration(vn);
  const ImpactResult r = wallImpact(wallCase("hertz_mindlin", e, mu), {vt, 0, -vn}, tc / 400.0);
  const double tangentialImpulse = kMass * std::abs(r.velocity.x - vt);
  const double normalImpulse = kMass * (r.velocity.z + vn);
  EXPECT_LT(tangentialImpulse, mu * normalImpulse);
  const double contactPointAfter = r.velocity.x - r.angularVelocity.y * kRadius;  // v + w x (-R z)
  EXPECT_LT(std::abs(contactPointAfter), vt);
  EXPECT_GT(std::abs(contactPointAfter - vt), 0.1 * vt);  // the spring acted
  EXPECT_LT(std::abs(contactPointAfter - vt), 3.5 * mu * (1 + e) * vn);  // less than gross sliding
}

/// Two equal spheres in an oblique head-on impact (sticking, so the tangential spring holds
/// history), stepped until they part; then the same approach again from the start. The second
/// impact must be the first one bit for bit: the pair, still listed (within the skin), lost its
/// history when it stopped touching.
TEST(DemContact, PairThatPartsLosesItsHistoryAndRepeatsTheImpact) {
  for (const std::string law : {"hertz_mindlin", "hooke"}) {
    DemCase c(materialsYaml(law, 0.9, 0.5, 1e7, 0.3, law == "hooke" ? "  normal_stiffness: 1e4" : "") +
                  "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\n",
              {0, 0, 0});
    const Vec3 x0{-kRadius - 1e-7, 0, 0}, x1{kRadius + 1e-7, 0, 0}, v0{0.1, 0.004, 0}, v1{-0.1, -0.004, 0};
    c->particles().add(0, 0, kRadius, kDensity, x0, v0);
    c->particles().add(1, 0, kRadius, kDensity, x1, v1);
    auto impact = [&]() {
      ParticleSet& p = c->particles();
      p.position[0] = x0;
      p.position[1] = x1;
      p.velocity[0] = v0;
      p.velocity[1] = v1;
      p.angularVelocity[0] = p.angularVelocity[1] = Vec3{};
      c->refresh();
      bool touched = false, held = false;
      for (int s = 0; s < 200000; ++s) {
        c->step(2e-7);
        const NeighbourList& list = c->neighbourList();
        const bool touching = p.position[1].x - p.position[0].x < 2.0 * kRadius;
        if (touching) {
          touched = true;
          held = held || (list.entries() == 1 && anyBitSet(list.tangentialHistory[0]));
        } else if (touched) {
          EXPECT_EQ(list.entries(), 1u) << law;  // still listed
          if (list.entries() == 1) {
            EXPECT_FALSE(anyBitSet(list.tangentialHistory[0])) << law;
          }
          break;
        }
      }
      EXPECT_TRUE(touched && held) << law;
      return std::pair<Vec3, Vec3>{p.velocity[1] - p.velocity[0], p.angularVelocity[0]};
    };
    const auto first = impact();
    const auto second = impact();
    EXPECT_GT(std::abs(first.second.z), 0.0) << law;  // the tangential spring spun the spheres
    EXPECT_EQ(first.first, second.first) << law;
    EXPECT_EQ(first.second, second.second) << law;
  }
}

/// Sphere released on an incline (gravity tilted by theta), returns acceleration along the slope.
double inclineAcceleration(const std::string& law, double thetaDeg, double mu, double rollingFriction = 0.0,
                           const std::string& rolling = "none") {
  const double theta = thetaDeg * std::numbers::pi / 180.0, g = 9.81;
  const Vec3 gravity{g * std::sin(theta), 0, -g * std::cos(theta)};
  std::string yaml = materialsYaml(law, 0.1, mu, 1e7, 0.3,
                                   fmt::format("{}  rolling: {}\n  rolling_friction: {}",
                                               law == "hooke" ? "  normal_stiffness: 1e4\n" : "", rolling,
                                               rollingFriction)) +
                     R"(
domain: {min: [-1, -0.01, -0.01], max: [1, 0.01, 0.01]}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
)";
  DemCase c(yaml, gravity);
  c->particles().add(0, 0, kRadius, kDensity, {0, 0, kRadius * 0.999});
  c->refresh();
  const double dt = 2e-6;
  for (int s = 0; s < 10000; ++s) c->step(dt);  // settle the normal contact
  const double v0 = c->particles().velocity[0].x;
  const int n = 20000;
  for (int s = 0; s < n; ++s) c->step(dt);
  return (c->particles().velocity[0].x - v0) / (n * dt);
}

TEST(DemContact, InclineRollsWithFiveSeventhsGSinTheta) {
  const double g = 9.81;
  for (double thetaDeg : {10.0, 20.0}) {  // tan(theta) < 3.5 mu = 1.75
    const double expected = 5.0 / 7.0 * g * std::sin(thetaDeg * std::numbers::pi / 180.0);
    EXPECT_NEAR(inclineAcceleration("hertz_mindlin", thetaDeg, 0.5), expected, 0.01 * expected);
    EXPECT_NEAR(inclineAcceleration("hooke", thetaDeg, 0.5), expected, 0.01 * expected);
  }
}

TEST(DemContact, InclineSlidesWhenTanThetaExceedsThreePointFiveMu) {
  const double g = 9.81, theta = 30.0 * std::numbers::pi / 180.0, mu = 0.1;  // tan 30 = 0.577 > 0.35
  const double expected = g * (std::sin(theta) - mu * std::cos(theta));
  EXPECT_NEAR(inclineAcceleration("hertz_mindlin", 30.0, mu), expected, 0.01 * expected);
}

// Constant rolling torque mu_r R F_n decelerates a rolling sphere at a = mu_r g / (1 + I/(m R^2))
// = mu_r g / 1.4 (Ai et al. 2011): stopping distance s = 0.7 v0^2 / (mu_r g).
TEST(DemContact, RollingResistanceStopsSphereAtAnalyticDistance) {
  const double g = 9.81, v0 = 0.05;
  for (const std::string model : {"constant_torque", "epsd"}) {
    const double muR = 0.05;
    std::string yaml = materialsYaml("hertz_mindlin", 0.1, 0.5, 1e7, 0.3,
                                     fmt::format("  rolling: {}\n  rolling_friction: {}", model, muR)) +
                       R"(
domain: {min: [-1, -0.01, -0.01], max: [1, 0.01, 0.01]}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
)";
    DemCase c(yaml, {0, 0, -g});
    c->particles().add(0, 0, kRadius, kDensity, {0, 0, kRadius * 0.99995});
    c->refresh();
    const double dt = 2e-6;
    for (int s = 0; s < 5000; ++s) c->step(dt);  // settle
    c->particles().velocity[0].x = v0;
    c->particles().angularVelocity[0].y = v0 / kRadius;  // pure rolling: v = -w x (-R z) -> w_y = v/R
    const double x0 = c->particles().position[0].x;
    double travelled = 0.0;
    for (int s = 0; s < 2000000; ++s) {
      c->step(dt);
      if (c->particles().velocity[0].x <= 0.0) break;
      travelled = c->particles().position[0].x - x0;
    }
    const double expected = 0.7 * v0 * v0 / (muR * g);
    EXPECT_NEAR(travelled, expected, 0.03 * expected) << model;
  }
}

}  // namespace
}  // namespace gf::dem
