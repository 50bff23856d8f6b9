#pragma once
// One contact, all composed models: the function the particle-particle and the particle-wall
// loops call, compiled once per (normal law, rolling law, cohesion law) combination.
//
// Conventions: `normal` points from partner j to particle i; `relativeVelocity` is the velocity
// of i's surface relative to j's at the contact point; history vectors belong to i's view of the
// contact (j sees the negative). Returned force acts on i (j gets -force); torques are separate.
#include <algorithm>
#include <cmath>

#include "core/vec3.hpp"
#include "dem/contact/contact_law.hpp"
#include "dem/contact/fast_sqrt.hpp"
#include "dem/contact/hertz_mindlin.hpp"
#include "dem/contact/hooke.hpp"
#include "dem/contact/rolling_resistance.hpp"
#include "dem/contact/simplified_jkr.hpp"

namespace gf::dem {

struct ContactGeometry {
  Vec3 normal;              // unit, from j to i
  double overlap;           // m, > 0
  Vec3 relativeVelocity;    // m/s at the contact point, i relative to j
  Vec3 relativeAngularVelocity;  // omega_i - omega_j, rad/s
  double effectiveRadius;   // R* (R_i for a wall)
  double effectiveMass;     // m* (m_i for a wall)
  double rollingInertia;    // I_r (EPSD only)
};

struct ContactResult {
  Vec3 force;         // on i, N
  Vec3 tangential;    // tangential part of force (for the torque r x F_t), N
  Vec3 rollingTorque; // on i (j gets the negative), N m
  double normalForce; // repulsive normal force magnitude (without cohesion), N
};

/// Rotates a history vector into the current tangent plane, keeping its length. In a lasting
/// contact the normal turns by ~1e-6 rad per step, so (h.n)^2/|h|^2 ~ 1e-12: the rescaling
/// (a square root and a division) is skipped below 1e-10, a relative length change of < 5e-11.
/// BranchFree (the batched loop, which vectorises): both outcomes computed, one selected; the
/// scalar form (wall contacts) skips the rare rescaling. Same results.
template <bool BranchFree = false>
[[gnu::always_inline]] inline void projectOntoTangentPlane(Vec3& h, const Vec3& n) {
  const double before = normSquared(h);
  const double hn = dot(h, n);
  h -= hn * n;
  if constexpr (BranchFree) {
    const double after = normSquared(h);
    const bool rescale = (hn * hn > 1e-10 * before) & (after > 0.0);
    const double scale = sqrtNonNegative(before / (after > 0.0 ? after : 1.0));
    h *= rescale ? scale : 1.0;  // x 1.0 is exact
  } else {
    if (hn * hn <= 1e-10 * before) return;
    const double after = normSquared(h);
    if (after > 0.0) h *= sqrtNonNegative(before / after);
  }
}

/// Per-component choice between two vectors (compiles to blends, no branch).
[[gnu::always_inline]] inline Vec3 select(bool condition, const Vec3& a, const Vec3& b) {
  return {condition ? a.x : b.x, condition ? a.y : b.y, condition ? a.z : b.z};
}

/// BranchFree: see projectOntoTangentPlane (the Coulomb limit likewise); same results.
template <NormalLaw N, RollingLaw R, CohesionLaw C, bool BranchFree = false>
[[gnu::always_inline]] inline ContactResult contactForce(const PairCoefficients& c, const ContactGeometry& g,
                                                         Vec3& tangentialHistory, Vec3* rollingHistory, double dt) {
  const Vec3& n = g.normal;
  const double vn = dot(g.relativeVelocity, n);  // < 0 while approaching
  const Vec3 vt = g.relativeVelocity - vn * n;
  double elastic, gammaN, kt, knLinear;
  if constexpr (N == NormalLaw::HertzMindlin) {
    // One square root for all Hertz-Mindlin terms: sqrt(R* d) (see hertz_mindlin.hpp).
    const double sqrtRd = sqrtNonNegative(g.effectiveRadius * g.overlap);
    const double kHertzSqrtD = 4.0 / 3.0 * c.effectiveYoungs * sqrtRd;  // k_hz sqrt(d)
    elastic = kHertzSqrtD * g.overlap;
    gammaN = c.damping * sqrtNonNegative(g.effectiveMass * kHertzSqrtD);
    kt = 8.0 * c.effectiveShear * sqrtRd;
    knLinear = 1.5 * kHertzSqrtD;
  } else {
    elastic = c.normalStiffness * g.overlap;
    gammaN = hooke::dampingCoefficient(c.damping, c.normalStiffness, g.effectiveMass);
    kt = c.tangentialStiffness;
    knLinear = c.normalStiffness;
  }
  // No tensile contact force (the damping may not pull the surfaces together).
  const double normalForce = std::max(0.0, elastic - gammaN * vn);
  double normalTotal = normalForce;
  if constexpr (C == CohesionLaw::SimplifiedJkr)
    normalTotal -= cohesion::simplifiedJkrForce(c.cohesionEnergyDensity, g.effectiveRadius, g.overlap);

  // Tangential spring with Coulomb limit (Cundall & Strack 1979; Mindlin stiffness for Hertz).
  projectOntoTangentPlane<BranchFree>(tangentialHistory, n);
  tangentialHistory += dt * vt;
  const double gammaT = gammaN * c.tangentialDampingRatio;
  Vec3 ft = -kt * tangentialHistory - gammaT * vt;
  const double ftMax = c.friction * normalForce;
  const double ftMag2 = normSquared(ft);
  if constexpr (BranchFree) {
    // Sliding: F_t scaled back onto the Coulomb limit, the spring set to match it. Computed
    // always and selected; the unused lanes may hold inf/NaN, never selected.
    const bool sliding = ftMag2 > ftMax * ftMax;
    const Vec3 ftSliding = (ftMax / sqrtNonNegative(ftMag2)) * ft;
    const Vec3 historySliding = select(kt > 0.0, (-1.0 / kt) * (ftSliding + gammaT * vt), Vec3{});
    ft = select(sliding, ftSliding, ft);
    tangentialHistory = select(sliding, historySliding, tangentialHistory);
  } else if (ftMag2 > ftMax * ftMax) {
    ft *= ftMax / sqrtNonNegative(ftMag2);
    tangentialHistory = (kt > 0.0) ? (-1.0 / kt) * (ft + gammaT * vt) : Vec3{};
  }

  ContactResult r;
  r.force = normalTotal * n + ft;
  r.tangential = ft;
  r.normalForce = normalForce;
  if constexpr (R != RollingLaw::None) {
    Vec3 wt = g.relativeAngularVelocity - dot(g.relativeAngularVelocity, n) * n;
    if constexpr (R == RollingLaw::ConstantTorque) {
      r.rollingTorque = rolling::constantTorque(c.rollingFriction, g.effectiveRadius, normalForce, wt);
    } else {
      projectOntoTangentPlane<BranchFree>(*rollingHistory, n);
      const double kr = rolling::epsdStiffness(knLinear, c.rollingFriction, g.effectiveRadius);
      r.rollingTorque = rolling::epsdTorque(*rollingHistory, kr, c.rollingFriction * g.effectiveRadius * normalForce,
                                            c.rollingDamping, g.rollingInertia, wt, dt);
    }
  }
  (void)knLinear;
  return r;
}

}  // namespace gf::dem
