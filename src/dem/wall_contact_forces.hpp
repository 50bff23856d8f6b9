#pragma once
// The wall contact forces of one particle (wallContactsOfParticle), with the de-duplication of
// mesh contacts: the contact sweep's path for walls with triangle meshes (plain walls go through
// the wall batch of block_sweep.hpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"
#include "dem/contact/contact_force.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/particles.hpp"
#include "dem/wall_contact_list.hpp"
#include "dem/walls/wall.hpp"

namespace gf::dem {

/// Current state of the walls, as the contact loop sees it.
struct WallState {
  const std::vector<WallPrimitive>* primitives;
  const std::vector<int>* material;    // per wall
  const std::vector<Vec3>* velocity;   // per wall, translation
  const std::vector<Vec3>* angularVelocity;
  const std::vector<Vec3>* centre;     // per wall, current
  bool hasTriangles = false;           // any triangle primitive (mesh contacts are de-duplicated)
  bool allPlanes = false;              // every primitive a plane (box walls, distributor plates)
};

/// A touching triangle of a mesh, before de-duplication.
struct TriangleTouch {
  std::uint32_t entry;
  WallDistance distance;
  int rank;  // 0: face contact, 1: edge/vertex contact with history, 2: edge/vertex contact without
};

/// Adds the wall contact forces of particle i (touches only particle i and its wall entries).
///
/// Triangle meshes: a sphere touching a shared edge or vertex sees the same closest point on
/// every triangle that shares it. Like LIGGGHTS (mesh contact de-duplication), face contacts are
/// accepted first, then edge/vertex contacts (those with tangential history first, so a lasting
/// contact keeps its history); a contact is dropped if its contact point lies on a triangle of the
/// same wall that was already accepted. A sphere on an edge or vertex gets one contact; a sphere
/// in a concave corner keeps one contact per face.
///
/// add(force, torque) adds one contact's force and torque to the particle (or logs them:
/// PartnerBuffers::deferred).
template <NormalLaw N, RollingLaw R, CohesionLaw C, class Add>
inline void wallContactsOfParticle(ParticleSet& p, WallContactList& list, const ContactTable& table,
                                   const WallState& walls, double dt, std::size_t i, Add&& add) {
  const std::uint32_t first = list.rowStart[i], last = list.rowStart[i + 1];
  if (first == last) return;
  const int types = table.count();
  const PairCoefficients* coefficients = table.data();
  const Vec3 xi = p.position[i], vi = p.velocity[i], wi = p.angularVelocity[i];
  const double ri = p.radius[i], mi = p.mass[i];
  auto clear = [&](std::uint32_t k) {
    list.tangentialHistory[k] = Vec3{};
    if constexpr (R == RollingLaw::Epsd) list.rollingHistory[k] = Vec3{};
    list.force[k] = Vec3{};
  };
  auto apply = [&](std::uint32_t k, const WallPrimitive& prim, const WallDistance& wd) {
    const int w = prim.wall;
    const Vec3 contactPoint = xi - wd.distance * wd.normal;
    const Vec3 ww = (*walls.angularVelocity)[w];
    const Vec3 wallVelocity = (*walls.velocity)[w] + cross(ww, contactPoint - (*walls.centre)[w]);
    ContactGeometry g;
    g.normal = wd.normal;
    g.overlap = ri - wd.distance;
    g.relativeVelocity = vi - ri * cross(wi, g.normal) - wallVelocity;
    g.relativeAngularVelocity = wi - ww;
    g.effectiveRadius = ri;
    g.effectiveMass = mi;
    if constexpr (R == RollingLaw::Epsd) g.rollingInertia = 1.4 * mi * ri * ri;
    const ContactResult c = contactForce<N, R, C>(coefficients[p.type[i] * types + (*walls.material)[w]], g,
                                                  list.tangentialHistory[k],
                                                  R == RollingLaw::Epsd ? &list.rollingHistory[k] : nullptr, dt);
    add(c.force, c.rollingTorque - ri * cross(g.normal, c.tangential));
    list.force[k] = c.force;
    list.point[k] = contactPoint;
  };
  if (!walls.hasTriangles) {
    for (std::uint32_t k = first; k < last; ++k) {
      const WallPrimitive& prim = (*walls.primitives)[list.primitive[k]];
      const WallDistance wd = prim.active ? distanceToPrimitive(prim, xi) : WallDistance{1e300, {}};
      if (wd.distance >= ri) clear(k);
      else apply(k, prim, wd);
    }
    return;
  }
  thread_local std::vector<TriangleTouch> touches;
  touches.clear();
  for (std::uint32_t k = first; k < last; ++k) {
    const WallPrimitive& prim = (*walls.primitives)[list.primitive[k]];
    if (!prim.active) {
      clear(k);
      continue;
    }
    if (prim.kind == PrimitiveKind::Triangle) {
      bool onFace = false;
      const Vec3 d = xi - closestPointOnTriangle(xi, prim.a, prim.b, prim.c, &onFace);
      const double dist2 = normSquared(d);
      if (dist2 >= ri * ri) {
        clear(k);
        continue;
      }
      const double dist = std::sqrt(dist2);
      const int rank = onFace ? 0 : (list.tangentialHistory[k] != Vec3{} ? 1 : 2);
      touches.push_back({k, {dist, dist > 0.0 ? d / dist : Vec3{}}, rank});
      continue;
    }
    const WallDistance wd = distanceToPrimitive(prim, xi);
    if (wd.distance >= ri) clear(k);
    else apply(k, prim, wd);
  }
  if (touches.empty()) return;
  std::stable_sort(touches.begin(), touches.end(),
                   [](const TriangleTouch& a, const TriangleTouch& b) { return a.rank < b.rank; });
  const double tolerance = 1e-6 * ri;
  for (std::size_t q = 0; q < touches.size(); ++q) {
    const WallPrimitive& prim = (*walls.primitives)[list.primitive[touches[q].entry]];
    const Vec3 contactPoint = xi - touches[q].distance.distance * touches[q].distance.normal;
    bool duplicate = false;
    for (std::size_t a = 0; a < q && !duplicate; ++a) {
      if (touches[a].rank < 0) continue;  // dropped itself
      const WallPrimitive& accepted = (*walls.primitives)[list.primitive[touches[a].entry]];
      duplicate = accepted.wall == prim.wall && pointOnTriangle(accepted, contactPoint, tolerance);
    }
    if (duplicate) {
      clear(touches[q].entry);
      touches[q].rank = -1;
    } else {
      apply(touches[q].entry, prim, touches[q].distance);
    }
  }
}

}  // namespace gf::dem
