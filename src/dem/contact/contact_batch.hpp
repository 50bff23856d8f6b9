#pragma once
// Batched particle-particle contacts: the touching pairs of a run of neighbour-list rows are
// gathered into small structure-of-arrays scratch arrays, evaluated in one straight loop without
// branches (contactForce is branch-free for the rolling-free laws, so the compiler vectorises the
// loop; the square roots and divisions of several contacts then overlap instead of forming one
// long latency chain per contact), and scattered back in list order by the caller. Every value is
// computed with the same operations in the same order as one contact at a time: same results.
#include <cstdint>

#include "core/cpu_features.hpp"  // GF_VECTOR_CLONES: the evaluation loop also for AVX2 / AVX-512
#include "core/vec3.hpp"
#include "dem/contact/contact_force.hpp"

namespace gf::dem {

/// Scratch arrays of one batch (per thread; fixed size, so that the compiler sees that the arrays
/// do not overlap). Inputs are filled by the gather, outputs by evaluateBatch().
struct ContactBatch {
  static constexpr std::uint32_t kCapacity = 256;  // candidates (neighbour-list entries) per batch
  static constexpr std::uint32_t kRowFill = 8;     // owner entries written per row without a loop

  std::uint32_t size = 0;  // touching pairs gathered
  bool uniform = true;     // all pairs of the batch use coefficients pairIndex[0]
  // Every particle has the same radius and mass (a bed of identical spheres, one material): the
  // gather then leaves ri, rj, mi, mj and pairIndex[1..] unwritten, and the evaluation takes
  // these two values (and pairIndex[0]) for every pair. Same operations: same results.
  bool identical = false;
  double identicalRadius = 0.0, identicalMass = 0.0;
  /// Identical spheres without rolling resistance: the evaluation stores only r n x F_t (in
  /// tix/y/z), from which the scatter forms both torques.
  template <RollingLaw R>
  bool torqueArm() const { return identical && R == RollingLaw::None; }
  // Rows of the run (index in the run: particle rb + row).
  alignas(64) std::uint32_t owner[kCapacity + kRowFill];  // row of each candidate
  alignas(64) std::uint32_t row[kCapacity];               // row of each touching pair
  Vec3 rowForce[kCapacity], rowTorque[kCapacity];         // sums of each row's pairs
  // Inputs.
  alignas(64) std::uint32_t entry[kCapacity];      // neighbour-list entry k
  alignas(64) std::uint32_t partner[kCapacity];    // particle j
  alignas(64) std::uint32_t pairIndex[kCapacity];  // coefficient index type_i * types + type_j
  alignas(64) double dx[kCapacity], dy[kCapacity], dz[kCapacity];  // x_i - x_j (minimum image)
  alignas(64) double dvx[kCapacity], dvy[kCapacity], dvz[kCapacity];  // v_i - v_j
  alignas(64) double sx[kCapacity], sy[kCapacity], sz[kCapacity];     // r_i w_i + r_j w_j
  alignas(64) double dwx[kCapacity], dwy[kCapacity], dwz[kCapacity];  // w_i - w_j (rolling laws)
  alignas(64) double ri[kCapacity], rj[kCapacity], mi[kCapacity], mj[kCapacity];
  alignas(64) double hx[kCapacity], hy[kCapacity], hz[kCapacity];     // tangential history, in/out
  alignas(64) double rhx[kCapacity], rhy[kCapacity], rhz[kCapacity];  // rolling history (EPSD), in/out
  // Outputs.
  alignas(64) double fx[kCapacity], fy[kCapacity], fz[kCapacity];     // force on i (j: the negative)
  alignas(64) double tix[kCapacity], tiy[kCapacity], tiz[kCapacity];  // torque on i (TorqueArm: r n x F_t)
  alignas(64) double tjx[kCapacity], tjy[kCapacity], tjz[kCapacity];  // torque on j
};

/// Lane e of three scratch arrays (x, y, z components) as a vector, and back.
[[gnu::always_inline]] inline Vec3 loadLane(const double* x, const double* y, const double* z, std::uint32_t e) {
  return {x[e], y[e], z[e]};
}
[[gnu::always_inline]] inline void storeLane(double* x, double* y, double* z, std::uint32_t e, const Vec3& v) {
  x[e] = v.x;
  y[e] = v.y;
  z[e] = v.z;
}

/// Evaluates the contact law for every gathered pair (contactForce, as for one contact).
template <NormalLaw N, RollingLaw R, CohesionLaw C, bool Uniform, bool Identical = false>
GF_VECTOR_CLONES void evaluateBatchAs(ContactBatch& b, const PairCoefficients* coefficients, double dt) {
  const std::uint32_t count = b.size;
  const PairCoefficients uniformPair = coefficients[b.pairIndex[0]];
  const double radius = b.identicalRadius, mass = b.identicalMass;
  for (std::uint32_t e = 0; e < count; ++e) {
    const Vec3 d{b.dx[e], b.dy[e], b.dz[e]};
    const double dist = sqrtNonNegative(normSquared(d));  // as in the gather's contact test
    const double ri = Identical ? radius : b.ri[e], rj = Identical ? radius : b.rj[e];
    const double mi = Identical ? mass : b.mi[e], mj = Identical ? mass : b.mj[e];
    const double rsum = ri + rj;
    ContactGeometry g;
    g.normal = (1.0 / dist) * d;
    g.overlap = rsum - dist;
    g.relativeVelocity = Vec3{b.dvx[e], b.dvy[e], b.dvz[e]} - cross(Vec3{b.sx[e], b.sy[e], b.sz[e]}, g.normal);
    if constexpr (R != RollingLaw::None) g.relativeAngularVelocity = {b.dwx[e], b.dwy[e], b.dwz[e]};
    // R* = r_i r_j/(r_i + r_j) and m* = m_i m_j/(m_i + m_j) with one division.
    const double msum = mi + mj;
    const double inv = 1.0 / (rsum * msum);
    g.effectiveRadius = ri * rj * msum * inv;
    g.effectiveMass = mi * mj * rsum * inv;
    if constexpr (R == RollingLaw::Epsd)
      g.rollingInertia = 1.0 / (1.0 / (1.4 * mi * ri * ri) + 1.0 / (1.4 * mj * rj * rj));
    Vec3 history = loadLane(b.hx, b.hy, b.hz, e);
    Vec3 rollingHistory{};
    if constexpr (R == RollingLaw::Epsd) rollingHistory = loadLane(b.rhx, b.rhy, b.rhz, e);
    const PairCoefficients& c = Uniform ? uniformPair : coefficients[b.pairIndex[e]];
    const ContactResult r = contactForce<N, R, C, true>(c, g, history, &rollingHistory, dt);
    // Torque of the tangential force: -R n x F_t on both (contact point -R_i n from i, +R_j n from j).
    const Vec3 nxf = cross(g.normal, r.tangential);
    storeLane(b.fx, b.fy, b.fz, e, r.force);
    if constexpr (Identical && R == RollingLaw::None) {
      // r_i = r_j, no rolling torque: ti = 0 - r n x F_t and tj = -r n x F_t (the same bits as
      // the general lines below) both follow from r n x F_t, which is all the batch keeps.
      storeLane(b.tix, b.tiy, b.tiz, e, ri * nxf);
    } else {
      const Vec3 ti = r.rollingTorque - ri * nxf;
      const Vec3 tj = -rj * nxf - r.rollingTorque;
      storeLane(b.tix, b.tiy, b.tiz, e, ti);
      storeLane(b.tjx, b.tjy, b.tjz, e, tj);
    }
    storeLane(b.hx, b.hy, b.hz, e, history);
    if constexpr (R == RollingLaw::Epsd) storeLane(b.rhx, b.rhy, b.rhz, e, rollingHistory);
  }
}

template <NormalLaw N, RollingLaw R, CohesionLaw C>
inline void evaluateBatch(ContactBatch& b, const PairCoefficients* coefficients, double dt) {
  if (b.size == 0) return;
  if (b.identical) evaluateBatchAs<N, R, C, true, true>(b, coefficients, dt);
  else if (b.uniform) evaluateBatchAs<N, R, C, true>(b, coefficients, dt);
  else evaluateBatchAs<N, R, C, false>(b, coefficients, dt);
}

}  // namespace gf::dem
