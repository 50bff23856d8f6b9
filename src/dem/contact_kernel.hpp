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
// driver that runs the sweeps and completes the receiving rows.
#include <omp.h>

#include <cstddef>
#include <vector>

#include "core/cpu_features.hpp"
#include "core/parallel.hpp"
#include "dem/block_sweep.hpp"
#include "dem/contact/contact_batch.hpp"
#include "dem/contact/contact_force.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/contact/wall_batch.hpp"
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

/// Sets force = body forces + particle-particle + particle-wall contact forces, then (if
/// halfKick != 0) applies the closing velocity-Verlet half kick v += halfKick F/m, w += halfKick T/I
/// to each thread's block once its forces are final (one pass less over memory). Each thread
/// sweeps its block of rows (BlockSweep), then completes its receiving rows from the logs of the
/// threads before it and its own (PartnerBuffers).
template <NormalLaw N, RollingLaw R, CohesionLaw C>
void contactForcesAndKick(ParticleSet& p, NeighbourList& list, WallContactList& wallList, const WallState& walls,
                          const ContactTable& table, const PeriodicBox& box, const Vec3& gravity, double dt,
                          double halfKick, const InverseInertia& inverse, PartnerBuffers& buffers) {
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
  common.inverseMass = inverse.mass;
  common.inverseMoment = inverse.moment;
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
  common.halfKick = halfKick;
  common.external = p.hasExternalForces;
  common.externalTorques = p.hasExternalTorques;
  common.attribute = identicalIndexMask(inverse.identical);
  common.withWalls = !walls.primitives->empty();
  common.batchWalls = common.withWalls && !walls.hasTriangles;
  Vec3* force = p.force.data();
  Vec3* torque = p.torque.data();
  Vec3* velocity = p.velocity.data();
  Vec3* angularVelocity = p.angularVelocity.data();
  const double* inverseMass = inverse.mass;
  const double* inverseMoment = inverse.moment;
  auto kick = [&](std::size_t i) {
    velocity[i] += (halfKick * inverseMass[i]) * force[i];
    angularVelocity[i] += (halfKick * inverseMoment[i]) * torque[i];
  };
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
    sweep.kickHere = halfKick != 0.0;
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
    // that every force is summed in the one-thread order (PartnerBuffers); then their kicks.
    //
    // The receiving rows are particles the earlier blocks' threads read in their sweeps: each
    // store of a kick meets a line that the other core holds unless it was requested for writing
    // first. The requests go out one row per replayed entry, so that the lines arrive while the
    // logs are replayed (settled bed, 2 threads: the kicks of ~590 rows 10-11 -> 6.5 us per step,
    // the merge 19-21 -> 16-17 us; it is on the step's critical path, the other threads wait at
    // the region's end), then 8 rows ahead of the kicks for any left.
    const std::vector<std::uint32_t>& received = buffers.received[t];
    const bool requestLines = cpuHasPrefetchW() && halfKick != 0.0;
    std::size_t requested = 0;
    auto requestNextRow = [&]() {
      if (requestLines && requested < received.size()) {
        prefetchForWrite(velocity + received[requested]);
        prefetchForWrite(angularVelocity + received[requested]);
        ++requested;
      }
    };
    for (int s = 0; s < t; ++s)
      for (const LoggedContribution& c : buffers.outgoing[s]) {
        requestNextRow();
        if (c.particle < begin || c.particle >= end) continue;  // (another later block's)
        force[c.particle] += c.force;
        torque[c.particle] += c.torque;
      }
    for (const LoggedContribution& c : buffers.deferred[t]) {
      requestNextRow();
      force[c.particle] += c.force;
      torque[c.particle] += c.torque;
    }
    if (halfKick == 0.0) return;
    constexpr std::size_t kAhead = 8;
    for (std::size_t r = 0; r < received.size(); ++r) {
      if (requestLines && r + kAhead < received.size() && r + kAhead >= requested) {
        prefetchForWrite(velocity + received[r + kAhead]);
        prefetchForWrite(angularVelocity + received[r + kAhead]);
      }
      kick(received[r]);
    }
  };
  runTeam(threads, member);  // (a team of one: no region, core/parallel.hpp)
}

}  // namespace gf::dem
