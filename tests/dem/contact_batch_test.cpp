// The batched particle-particle force loop (src/dem/contact/contact_batch.hpp) on a neighbour-list
// row longer than one batch (a large sphere among small ones, evaluated in pieces) with two
// materials in one batch (per-pair coefficients): each contact must carry the Hertz force of its
// overlap, and the large sphere the sum of the reactions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/parallel.hpp"
#include "dem/contact/contact_batch.hpp"
#include "dem_test_util.hpp"

namespace gf::dem {
namespace {

using test::DemCase;

constexpr double kYoungsGlass = 1e7, kYoungsSteel = 5e7, kPoisson = 0.3;

std::string twoMaterialCase() {
  return R"(
materials:
  - {name: glass, density: 2500, youngs_modulus: 1e7, poisson_ratio: 0.3}
  - {name: steel, density: 7800, youngs_modulus: 5e7, poisson_ratio: 0.3}
contact: {law: hertz_mindlin, restitution: 0.5, friction: 0.5}
domain: {min: [-0.02, -0.02, -0.02], max: [0.02, 0.02, 0.02]}
neighbour_search: {reorder_interval: 0}
)";
}

struct Forces {
  std::vector<Vec3> force;
};

// Large glass sphere (index 0, so its half-list row holds all its neighbours) with `count` small
// spheres on a Fibonacci lattice over its surface, each overlapping it by `overlap`; every other
// small sphere is steel. No gravity, at rest: the forces are the elastic Hertz forces alone.
Forces forcesAroundLargeSphere(int threads, int count, double overlap) {
  setThreadCount(threads);
  DemCase c(twoMaterialCase(), {0, 0, 0});
  ParticleSet& p = c->particles();
  const double bigRadius = 0.005, smallRadius = 0.0004;
  p.add(0, 0, bigRadius, 2500, {0, 0, 0});
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < count; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / count, rho = std::sqrt(1.0 - z * z);
    const Vec3 n{rho * std::cos(golden * k), rho * std::sin(golden * k), z};
    p.add(k + 1, k % 2, smallRadius, k % 2 ? 7800 : 2500, (bigRadius + smallRadius - overlap) * n);
  }
  c->refresh();
  Forces out{c->particles().force};
  setThreadCount(1);
  return out;
}

TEST(DemContactBatch, RowLongerThanABatchGivesTheHertzForceOfEveryContact) {
  const int count = 300;  // > ContactBatch::kCapacity partners in one row; small spheres apart
  static_assert(300 > ContactBatch::kCapacity);
  const double overlap = 2e-6, bigRadius = 0.005, smallRadius = 0.0004;
  const Forces f = forcesAroundLargeSphere(1, count, overlap);
  ASSERT_EQ(f.force.size(), static_cast<std::size_t>(count + 1));
  // Hertz (Johnson 1985 eq. 4.22): F = 4/3 E* sqrt(R*) d^(3/2), 1/E* = (1-nu_1^2)/E_1 + (1-nu_2^2)/E_2
  // (Di Renzo & Di Maio 2004 eq. 5), R* = R r/(R + r).
  const double effectiveRadius = bigRadius * smallRadius / (bigRadius + smallRadius);
  Vec3 reactionSum{};
  for (int k = 0; k < count; ++k) {
    const double youngs = k % 2 ? kYoungsSteel : kYoungsGlass;
    const double effectiveYoungs = 1.0 / ((1.0 - kPoisson * kPoisson) / kYoungsGlass + (1.0 - kPoisson * kPoisson) / youngs);
    const double expected = 4.0 / 3.0 * effectiveYoungs * std::sqrt(effectiveRadius) * std::pow(overlap, 1.5);
    const Vec3& fk = f.force[k + 1];
    EXPECT_NEAR(norm(fk), expected, 1e-9 * expected) << "contact " << k;
    reactionSum += fk;
  }
  // The large sphere carries the reactions (Newton's third law, round-off only).
  EXPECT_LT(norm(f.force[0] + reactionSum), 1e-12 * count * norm(f.force[1]));
}

TEST(DemContactBatch, RowLongerThanABatchAgreesAcrossThreadCounts) {
  const Forces one = forcesAroundLargeSphere(1, 300, 2e-6);
  const Forces two = forcesAroundLargeSphere(2, 300, 2e-6);
  ASSERT_EQ(one.force.size(), two.force.size());
  for (std::size_t i = 1; i < one.force.size(); ++i) EXPECT_EQ(one.force[i], two.force[i]) << i;  // one contact each
  EXPECT_LT(norm(one.force[0] - two.force[0]), 1e-12 * 300 * norm(one.force[1]));  // summation order
}

}  // namespace
}  // namespace gf::dem
