#pragma once
// Batched particle-wall contacts (planes, cylinders, cones, disks; triangle meshes keep the
// one-particle-at-a-time path, which de-duplicates shared edges): the touching wall entries of a
// run of rows are gathered with their geometry (distance, normal, relative velocity at the contact
// point, computed as in wallContactsOfParticle), the contact law runs over them in one
// vectorised loop without branches (contactForce, BranchFree: same results as the scalar form),
// and the caller adds the results in list order. Same operations in the same order as one
// contact at a time: same results.
#include <cstdint>

#include "core/vec3.hpp"
#include "dem/contact/contact_batch.hpp"
#include "dem/contact/contact_force.hpp"

namespace gf::dem {

struct WallBatch {
  static constexpr std::uint32_t kCapacity = 256;  // wall entries of a run

  std::uint32_t size = 0;  // touching entries gathered
  bool uniform = true;     // all entries use coefficients pairIndex[0]
  alignas(64) std::uint32_t entry[kCapacity];             // wall-list entry k
  alignas(64) std::uint32_t row[kCapacity];               // run's row
  alignas(64) std::uint32_t pairIndex[kCapacity];         // type_i * types + material of the wall
  // Inputs (geometry: ContactGeometry of wallContactsOfParticle).
  alignas(64) double nx[kCapacity], ny[kCapacity], nz[kCapacity];     // unit normal, wall -> centre
  alignas(64) double overlap[kCapacity];                              // r_i - distance
  alignas(64) double vx[kCapacity], vy[kCapacity], vz[kCapacity];     // relative velocity at the point
  alignas(64) double wx[kCapacity], wy[kCapacity], wz[kCapacity];     // w_i - w_wall (rolling laws)
  alignas(64) double ri[kCapacity], mi[kCapacity], inertia[kCapacity];  // R*, m*, I_r (EPSD)
  alignas(64) double px[kCapacity], py[kCapacity], pz[kCapacity];     // contact point
  alignas(64) double hx[kCapacity], hy[kCapacity], hz[kCapacity];     // tangential history, in/out
  alignas(64) double rhx[kCapacity], rhy[kCapacity], rhz[kCapacity];  // rolling history (EPSD), in/out
  // Outputs.
  alignas(64) double fx[kCapacity], fy[kCapacity], fz[kCapacity];     // force on the particle
  alignas(64) double tx[kCapacity], ty[kCapacity], tz[kCapacity];     // torque on the particle
};

/// Evaluates the contact law for every gathered wall entry (as wallContactsOfParticle's apply).
template <NormalLaw N, RollingLaw R, CohesionLaw C, bool Uniform>
GF_VECTOR_CLONES void evaluateWallBatchAs(WallBatch& b, const PairCoefficients* coefficients, double dt) {
  const std::uint32_t count = b.size;
  const PairCoefficients uniformPair = coefficients[b.pairIndex[0]];
  for (std::uint32_t e = 0; e < count; ++e) {
    ContactGeometry g;
    g.normal = loadLane(b.nx, b.ny, b.nz, e);
    g.overlap = b.overlap[e];
    g.relativeVelocity = loadLane(b.vx, b.vy, b.vz, e);
    if constexpr (R != RollingLaw::None) g.relativeAngularVelocity = {b.wx[e], b.wy[e], b.wz[e]};
    const double ri = b.ri[e];
    g.effectiveRadius = ri;
    g.effectiveMass = b.mi[e];
    if constexpr (R == RollingLaw::Epsd) g.rollingInertia = b.inertia[e];
    Vec3 history = loadLane(b.hx, b.hy, b.hz, e);
    Vec3 rollingHistory{};
    if constexpr (R == RollingLaw::Epsd) rollingHistory = loadLane(b.rhx, b.rhy, b.rhz, e);
    const PairCoefficients& c = Uniform ? uniformPair : coefficients[b.pairIndex[e]];
    const ContactResult r = contactForce<N, R, C, true>(c, g, history, &rollingHistory, dt);
    const Vec3 t = r.rollingTorque - ri * cross(g.normal, r.tangential);
    storeLane(b.fx, b.fy, b.fz, e, r.force);
    storeLane(b.tx, b.ty, b.tz, e, t);
    storeLane(b.hx, b.hy, b.hz, e, history);
    if constexpr (R == RollingLaw::Epsd) storeLane(b.rhx, b.rhy, b.rhz, e, rollingHistory);
  }
}

template <NormalLaw N, RollingLaw R, CohesionLaw C>
inline void evaluateWallBatch(WallBatch& b, const PairCoefficients* coefficients, double dt) {
  if (b.size == 0) return;
  if (b.uniform) evaluateWallBatchAs<N, R, C, true>(b, coefficients, dt);
  else evaluateWallBatchAs<N, R, C, false>(b, coefficients, dt);
}

}  // namespace gf::dem
