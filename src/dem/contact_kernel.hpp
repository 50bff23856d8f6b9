#pragma once
// Force loops over the neighbour list and the wall contact list, compiled per contact-model
// combination (dispatchLaws picks one instantiation per call, before the loop).
//
// Determinism: rows are split into one contiguous block per thread (BlockSplit: by the listed
// work, weighted by each thread's measured speed). A thread writes the forces of its own block
// directly, except those of the rows that receive contributions from earlier blocks: those
// contributions, and its own to those rows, are logged in sweep order and added after the barrier
// in the one-thread order (PartnerBuffers). No atomics; the same bits on any split and thread count.
//
// Parts: the split of the rows (block_split.hpp), the logs the threads exchange
// (partner_buffers.hpp), one thread's sweep of its block (block_sweep.hpp) and the wall contacts
// of one particle (wall_contact_forces.hpp). This file: the choice of the instantiation and the
// driver that runs the sweeps and completes the receiving rows. The closing half kick follows
// as a pass of its own (half_kick.hpp).
#include <omp.h>

#include <cstddef>
#include <vector>

#include "core/parallel.hpp"
#include "dem/block_sweep.hpp"
#include "dem/contact/contact_batch.hpp"
#include "dem/contact/contact_force.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/contact/wall_batch.hpp"
#include "dem/half_kick.hpp"
#include "dem/neighbour_list.hpp"
#include "dem/partner_buffers.hpp"
#include "dem/particles.hpp"
#include "dem/wall_contact_forces.hpp"
#include "dem/wall_contact_list.hpp"

namespace gf::dem {

template <class F>
void dispatchLaws(NormalLaw n, RollingLaw r, CohesionLaw c, F&& f) {
  auto withCohesion = [&]<NormalLaw N, RollingLaw R>() {
    if (c == CohesionLaw::SimplifiedJkr) f.template operator()<N, R, CohesionLaw::SimplifiedJkr>();
    else f.template operator()<N, R, CohesionLaw::None>();
  };
  auto withRolling = [&]<NormalLaw N>() {
    if (r == RollingLaw::ConstantTorque) withCohesion.template operator()<N, RollingLaw::ConstantTorque>();
    else if (r == RollingLaw::Epsd) withCohesion.template operator()<N, RollingLaw::Epsd>();
    else withCohesion.template operator()<N, RollingLaw::None>();
  };
  if (n == NormalLaw::Hooke) withRolling.template operator()<NormalLaw::Hooke>();
  else withRolling.template operator()<NormalLaw::HertzMindlin>();
}

/// Sets force = body forces + particle-particle + particle-wall contact forces. Each thread sweeps
/// its block of rows (BlockSweep), then completes its receiving rows from the logs of the threads
/// before it and its own (PartnerBuffers). The closing half kick that uses these forces is a pass
/// of its own (closingHalfKick, half_kick.hpp). identical: every particle has particle 0's radius,
/// mass and type (identicalIndexMask).
template <NormalLaw N, RollingLaw R, CohesionLaw C>
void contactForces(ParticleSet& p, NeighbourList& list, WallContactList& wallList, const WallState& walls,
                   const ContactTable& table, const PeriodicBox& box, const Vec3& gravity, double dt, bool identical,
                   PartnerBuffers& buffers) {
  const std::size_t n = p.size();
  const int threads = omp_get_max_threads();
  BlockSweep<N, R, C> common{};
  common.particles = &p;
  common.force = p.force.data();
  common.torque = p.torque.data();
  common.velocity = p.velocity.data();
  common.angularVelocity = p.angularVelocity.data();
  common.position = p.position.data();
  common.radius = p.radius.data();
  common.mass = p.mass.data();
  common.type = p.type.data();
  common.externalForce = p.externalForce.data();
  common.externalTorque = p.externalTorque.data();
  common.rowStart = list.rowStart.data();
  common.partner = list.partner.data();
  common.history = list.tangentialHistory.data();
  common.rollingHistory = list.rollingHistory.data();
  common.wallList = &wallList;
  common.wallRowStart = wallList.rowStart.data();
  common.walls = &walls;
  common.table = &table;
  common.coefficients = table.data();
  common.types = static_cast<std::uint32_t>(table.count());
  common.box = box;
  common.gravity = gravity;
  common.dt = dt;
  common.external = p.hasExternalForces;
  common.externalTorques = p.hasExternalTorques;
  common.attribute = identicalIndexMask(identical);
  common.withWalls = !walls.primitives->empty();
  common.batchWalls = common.withWalls && !walls.hasTriangles;
  Vec3* force = p.force.data();
  Vec3* torque = p.torque.data();
  auto member = [&]() {
    const int t = omp_get_thread_num();
    const int team = omp_get_num_threads();
#pragma omp single
    buffers.prepare(team, n, list, wallList, !walls.primitives->empty());
    // (implicit barrier)
    const std::size_t begin = buffers.blockStart[t], end = buffers.blockStart[t + 1];
    thread_local ContactBatch batch;
    thread_local WallBatch wallBatch;
    BlockSweep<N, R, C> sweep = common;
    sweep.begin = begin;
    sweep.end = end;
    sweep.initialised = begin;
    sweep.laterBlocks = t < team - 1;
    sweep.outgoing = &buffers.outgoing[t];
    sweep.deferred = &buffers.deferred[t];
    sweep.receiving = t > 0 ? buffers.receives.data() : nullptr;
    sweep.batch = &batch;
    sweep.wallBatch = &wallBatch;
    if (team == 1) {
      sweep.run();
      return;
    }
    const double started = omp_get_wtime();
    sweep.run();
    buffers.recordSweep(t, omp_get_wtime() - started);
#pragma omp barrier
    if (t == 0) return;
    // Thread t completes its receiving rows (their force holds the body force): the earlier
    // blocks' contributions, block by block, each in sweep order, then its own deferred ones, so
    // that every force is summed in the one-thread order (PartnerBuffers).
    for (int s = 0; s < t; ++s)
      for (const LoggedContribution& c : buffers.outgoing[s]) {
        if (c.particle < begin || c.particle >= end) continue;  // (another later block's)
        force[c.particle] += c.force;
        torque[c.particle] += c.torque;
      }
    for (const LoggedContribution& c : buffers.deferred[t]) {
      force[c.particle] += c.force;
      torque[c.particle] += c.torque;
    }
  };
  runTeam(threads, member);  // (a team of one: no region, core/parallel.hpp)
}

}  // namespace gf::dem
