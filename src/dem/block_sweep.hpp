#pragma once
// One thread's pass over its block of rows of the half neighbour list (BlockSweep): gather of the
// touching pairs into batches, the contact law, the scatter in list order and the wall contacts.
// The driver that runs one sweep per thread and completes the receiving rows: contact_kernel.hpp.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/vec3.hpp"
#include "dem/contact/contact_batch.hpp"
#include "dem/contact/contact_force.hpp"
#include "dem/contact/contact_table.hpp"
#include "dem/contact/wall_batch.hpp"
#include "dem/half_kick.hpp"
#include "dem/partner_buffers.hpp"
#include "dem/particles.hpp"
#include "dem/periodic_box.hpp"
#include "dem/wall_contact_forces.hpp"
#include "dem/wall_contact_list.hpp"

namespace gf::dem {

/// One thread's pass over its block of rows [begin, end) of the half neighbour list (see
/// contactForces). Rows are processed in runs: the touching pairs of a run are gathered into a
/// ContactBatch, evaluated there in one vectorised loop, then added row by row in list order.
/// Force/torque of particle j are set to the body forces just before the first row that adds to
/// them (rows hold ascending partners j > i), so initialisation and contacts of a particle happen
/// while its data are in cache. The order of the additions is the same as with
/// a separate initialisation pass and one contact at a time.
template <NormalLaw N, RollingLaw R, CohesionLaw C>
struct BlockSweep {
  // Particles and lists.
  ParticleSet* particles;
  Vec3* force;
  Vec3* torque;
  Vec3* velocity;
  Vec3* angularVelocity;
  const Vec3* position;
  const double* radius;
  const double* mass;
  const std::int32_t* type;
  const Vec3* externalForce;
  const Vec3* externalTorque;
  const std::uint32_t* rowStart;
  const std::uint32_t* partner;
  Vec3* history;
  Vec3* rollingHistory;
  WallContactList* wallList;
  const std::uint32_t* wallRowStart;
  const WallState* walls;
  const ContactTable* table;
  const PairCoefficients* coefficients;
  std::uint32_t types;
  PeriodicBox box;
  Vec3 gravity;
  double dt;
  bool external, externalTorques, withWalls;
  std::uint32_t attribute = ~0u;  // index mask of radius, mass and type (identicalIndexMask)
  // Rows that receive contributions from earlier blocks (PartnerBuffers::receives; null in the
  // first block): their contributions go to `deferred`, added after the barrier.
  const std::uint8_t* receiving = nullptr;
  // This thread's block.
  std::size_t begin, end;
  bool laterBlocks;  // blocks follow this one: partners j >= end go to `outgoing`
  std::vector<LoggedContribution>* outgoing;
  std::vector<LoggedContribution>* deferred;
  std::size_t initialised;  // force/torque of [begin, initialised) hold the body forces
  ContactBatch* batch;
  // Wall contacts in batches (walls without triangle meshes).
  WallBatch* wallBatch;
  bool batchWalls;

  [[gnu::always_inline]] void initialiseUpTo(std::size_t stop) {
    std::size_t k = initialised;
    Vec3* __restrict const f = force;
    Vec3* __restrict const tq = torque;
    const double* __restrict const m = mass;
    const std::size_t at = attribute;  // (zero-extended: 0 or 2^32 - 1, above any particle index)
    const Vec3 g = gravity;
    if (external && externalTorques) {
      const Vec3* __restrict const fe = externalForce;
      const Vec3* __restrict const te = externalTorque;
      for (; k < stop; ++k) {
        f[k] = m[k & at] * g + fe[k];
        tq[k] = te[k];
      }
    } else if (external) {  // (external torques all zero: not read)
      const Vec3* __restrict const fe = externalForce;
      for (; k < stop; ++k) {
        f[k] = m[k & at] * g + fe[k];
        tq[k] = Vec3{};
      }
    } else {
      for (; k < stop; ++k) {
        f[k] = m[k & at] * g;
        tq[k] = Vec3{};
      }
    }
    initialised = std::max(initialised, stop);
  }
  /// Requests the data the gather reads of the far partners of row a (index beyond
  /// kNearPartners ahead of a), some rows before the gather needs them. Near partners come with
  /// the rows' own streams; a far one is a cache miss per array (at 1e6 particles the partner
  /// loads were ~60 % of the gather's time). Rows hold ascending partners: the far ones are last.
  static constexpr std::size_t kPrefetchRows = 16, kNearPartners = 128;
  /// Blocks of fewer rows than this fit the caches (with the lists, ~350 B per particle) and
  /// skip the prefetching (its exits cost more than it saves there: +10 % at 15,000 particles).
  static constexpr std::size_t kPrefetchFromRows = 50000;
  [[gnu::always_inline]] void prefetchFarPartners(std::size_t a) const {
    if (a >= end) return;
    const std::uint32_t first = rowStart[a];
    for (std::uint32_t k = rowStart[a + 1]; k > first;) {
      const std::uint32_t j = partner[--k];
      if (j < a + kNearPartners) break;
      __builtin_prefetch(position + j);
      __builtin_prefetch(velocity + j);
      __builtin_prefetch(angularVelocity + j);
      if (attribute != 0) {
        __builtin_prefetch(radius + j);
        __builtin_prefetch(mass + j);
        __builtin_prefetch(type + j);
      }
      // force and torque: written by the scatter (initialised long before for a far partner,
      // when the initialisation front passed it). Partners of other blocks go to the logs.
      const std::size_t own = std::min<std::size_t>(j, end - 1);
      __builtin_prefetch(force + own, 1);
      __builtin_prefetch(torque + own, 1);
    }
  }

  /// Requests the data of the partners of row a in later blocks (j >= end), some rows before the
  /// gather needs them. Those partners are the next thread's particles: their positions and
  /// velocities were last written by that thread (drift, kicks), so each is a transfer from the
  /// other core's cache. Without the request the first block's sweep took ~20 % longer than
  /// the second's for the same work (settled bed, 2 threads: ~1,750 such pairs per step). Rows
  /// hold ascending partners: the later-block ones are last.
  [[gnu::always_inline]] void prefetchLaterBlockPartners(std::size_t a) const {
    if (a >= end) return;
    const std::uint32_t first = rowStart[a];
    for (std::uint32_t k = rowStart[a + 1]; k > first;) {
      const std::uint32_t j = partner[--k];
      if (j < end) break;
      __builtin_prefetch(position + j);
      __builtin_prefetch(velocity + j);
      __builtin_prefetch(angularVelocity + j);
    }
  }

  /// Requests (for writing) every cache line of the entries [first, first + count) of an array.
  [[gnu::always_inline]] static void prefetchEntries(const Vec3* array, std::uint32_t first, std::uint32_t count) {
    const char* const end = reinterpret_cast<const char*>(array + first + count);
    for (const char* line = reinterpret_cast<const char*>(array + first); line < end; line += 64)
      __builtin_prefetch(line, 1);
  }

  /// Gathers the touching pairs among the candidates [base, base + count) of the rows of a run
  /// (rows [rb, ...), `b.owner[c]`: the run's row of candidate c) into the batch, with their
  /// history, and clears the history of all candidates. One flat loop over the candidates of all
  /// rows and one over the touching pairs: a loop exit per batch instead of two per row (a
  /// mispredicted branch each, rows hold ~6 candidates).
  [[gnu::always_inline]] void gatherRun(std::size_t rb, std::uint32_t base, std::uint32_t count,
                                        std::uint32_t start) {
    if (attribute == 0) gatherRunOf<true>(rb, base, count, start);
    else gatherRunOf<false>(rb, base, count, start);
  }
  /// Identical: every particle has particle 0's radius, mass and type (attribute == 0); the
  /// batch then holds no per-pair radii, masses or coefficient indices (ContactBatch::identical).
  template <bool Identical>
  [[gnu::always_inline]] void gatherRunOf(std::size_t rb, std::uint32_t base, std::uint32_t count,
                                          std::uint32_t start) {
    ContactBatch& b = *batch;
    const Vec3* const x = position + rb;
    const Vec3* const v = velocity + rb;
    const Vec3* const w = angularVelocity + rb;
    const double* const r = radius;
    const double* const m = mass;
    const std::uint32_t at = attribute;
    const auto rowIndex = static_cast<std::uint32_t>(rb);
    const std::uint32_t* const partnerOf = partner + base;
    const PeriodicBox localBox = box;  // a local copy: the batch stores cannot change it (no reloads)
    const double r0 = r[0], identicalSum = r0 + r0;
    std::uint32_t kept = start;
    for (std::uint32_t c = 0; c < count; ++c) {
      const std::uint32_t row = b.owner[c];
      const std::uint32_t j = partnerOf[c];
      const Vec3 d = localBox.minimumImage(x[row] - position[j]);
      const double rj = Identical ? r0 : r[j & at];
      const double dist2 = normSquared(d);
      const double rsum = Identical ? identicalSum : r[(rowIndex + row) & at] + rj;
      b.entry[kept] = base + c;
      b.row[kept] = row;
      b.partner[kept] = j;
      b.dx[kept] = d.x;
      b.dy[kept] = d.y;
      b.dz[kept] = d.z;
      if constexpr (!Identical) b.rj[kept] = rj;
      kept += !(dist2 >= rsum * rsum) ? 1u : 0u;  // touching: keep the entry
    }
    if constexpr (Identical) {
      b.identical = true;
      b.identicalRadius = r0;
      b.identicalMass = m[0];
      b.pairIndex[0] = static_cast<std::uint32_t>(type[0]) * types + static_cast<std::uint32_t>(type[0]);
      b.uniform = true;
      for (std::uint32_t e = start; e < kept; ++e) gatherPairMotion(b, e, v, w, r0, r0);
      b.size = kept;
      clearRunHistory(base, count);
      return;
    }
    b.identical = false;
    bool uniform = b.uniform;
    std::uint32_t firstPair = start > 0 ? b.pairIndex[0] : 0;
    for (std::uint32_t e = start; e < kept; ++e) {
      const std::uint32_t j = b.partner[e], row = b.row[e];
      const std::uint32_t i = (rowIndex + row) & at;  // (the row's particle for its constants)
      const double rowRadius = r[i];
      gatherPairMotion(b, e, v, w, rowRadius, b.rj[e]);
      b.ri[e] = rowRadius;
      b.mi[e] = m[i];
      b.mj[e] = m[j & at];
      const std::uint32_t pair = static_cast<std::uint32_t>(type[i]) * types + static_cast<std::uint32_t>(type[j & at]);
      b.pairIndex[e] = pair;
      if (e == 0) firstPair = pair;
      uniform = uniform && pair == firstPair;
    }
    b.uniform = uniform;
    b.size = kept;
    clearRunHistory(base, count);
  }

  /// Second gather loop, one touching pair e: its history (which travels with the touching entry:
  /// read here, for the touching pairs only), relative velocity dv, s = r_i w_i + r_j w_j and, with
  /// rolling resistance, the relative spin.
  [[gnu::always_inline]] void gatherPairMotion(ContactBatch& b, std::uint32_t e, const Vec3* v, const Vec3* w,
                                               double ri, double rj) const {
    const std::uint32_t j = b.partner[e], row = b.row[e];
    storeLane(b.hx, b.hy, b.hz, e, history[b.entry[e]]);
    if constexpr (R == RollingLaw::Epsd) {
      const Vec3 rh = rollingHistory[b.entry[e]];
      storeLane(b.rhx, b.rhy, b.rhz, e, rh);
    }
    const Vec3 wi = w[row], wj = angularVelocity[j];
    const Vec3 dv = v[row] - velocity[j];
    const Vec3 s = ri * wi + rj * wj;
    storeLane(b.dvx, b.dvy, b.dvz, e, dv);
    storeLane(b.sx, b.sy, b.sz, e, s);
    if constexpr (R != RollingLaw::None) {
      const Vec3 dw = wi - wj;
      storeLane(b.dwx, b.dwy, b.dwz, e, dw);
    }
  }

  /// The list keeps zero history (pairs not in contact lose theirs; the touching ones get theirs
  /// back in scatterRun): one block clear of the run's entries instead of a store per candidate.
  [[gnu::always_inline]] void clearRunHistory(std::uint32_t base, std::uint32_t count) const {
    std::memset(static_cast<void*>(history + base), 0, sizeof(Vec3) * count);
    if constexpr (R == RollingLaw::Epsd)
      std::memset(static_cast<void*>(rollingHistory + base), 0, sizeof(Vec3) * count);
  }

  /// Adds the evaluated pairs of the batch in list order: to their row's sum (b.rowForce/Torque,
  /// added to the row's particle in finishRun) and to the partners.
  template <bool Logs>
  [[gnu::always_inline]] void scatterRun() {
    const bool arm = batch->template torqueArm<R>();
    if constexpr (!Logs) {
      if (arm) scatterRunOf<true, false, false>();
      else scatterRunOf<false, false, false>();
    } else if (receiving) {
      if (arm) scatterRunOf<true, true, true>();
      else scatterRunOf<false, true, true>();
    } else {
      if (arm) scatterRunOf<true, false, true>();
      else scatterRunOf<false, false, true>();
    }
  }
  /// TorqueArm: ContactBatch::torqueArm (ti = 0 - y, tj = -y from y = r n x F_t, the bits of the
  /// general formulas). Deferring: this block has receiving rows (`receiving`), whose contributions
  /// are logged (PartnerBuffers). Logs: partners in later blocks may be listed (logged, `outgoing`).
  template <bool TorqueArm, bool Deferring, bool Logs>
  [[gnu::always_inline]] void scatterRunOf() {
    ContactBatch& b = *batch;
    Vec3* const f = force;
    Vec3* const tq = torque;
    Vec3* const h = history;
    const std::uint32_t blockEnd = static_cast<std::uint32_t>(end);
    const std::uint32_t count = b.size;
    for (std::uint32_t e = 0; e < count; ++e) {
      const std::uint32_t j = b.partner[e], k = b.entry[e], row = b.row[e];
      const Vec3 fe = loadLane(b.fx, b.fy, b.fz, e);
      Vec3 tqi, tqj;
      if constexpr (TorqueArm) {
        const Vec3 arm = loadLane(b.tix, b.tiy, b.tiz, e);
        tqi = Vec3{} - arm;
        tqj = Vec3{-arm.x, -arm.y, -arm.z};
      } else {
        tqi = loadLane(b.tix, b.tiy, b.tiz, e);
        tqj = loadLane(b.tjx, b.tjy, b.tjz, e);
      }
      b.rowForce[row] += fe;
      b.rowTorque[row] += tqi;
      h[k] = Vec3{b.hx[e], b.hy[e], b.hz[e]};
      if constexpr (R == RollingLaw::Epsd) rollingHistory[k] = Vec3{b.rhx[e], b.rhy[e], b.rhz[e]};
      // (logged: -fe is added where one thread subtracts fe; x + (-y) and x - y are the same bits)
      if (Logs && j >= blockEnd) {
        outgoing->push_back({-fe, tqj, j});
      } else if (Deferring && receiving[j]) {
        deferred->push_back({-fe, tqj, j});
      } else {
        f[j] -= fe;
        tq[j] += tqj;
      }
    }
  }

  /// Completes row i: its own sum and its wall contacts.
  template <bool Logs>
  [[gnu::always_inline]] void finishRow(std::size_t i, const Vec3& fi, const Vec3& tqi) {
    if (rowStart[i] < rowStart[i + 1]) addToRow<Logs>(i, fi, tqi);
    if (withWalls && wallRowStart[i] != wallRowStart[i + 1])
      wallContactsOfParticle<N, R, C>(*particles, *wallList, *table, *walls, dt, i,
                                      [&](const Vec3& f, const Vec3& t) { addToRow<Logs>(i, f, t); });
  }

  /// Adds a contribution to row i's own force and torque, or logs it (a receiving row: PartnerBuffers).
  /// Logs false: nothing is logged (a team of one), and the loops that call it hold no call.
  template <bool Logs>
  [[gnu::always_inline]] void addToRow(std::size_t i, const Vec3& f, const Vec3& t) {
    if (Logs && receiving && receiving[i]) {
      deferred->push_back({f, t, static_cast<std::uint32_t>(i)});
    } else {
      force[i] += f;
      torque[i] += t;
    }
  }

  /// Gathers the touching wall entries of rows [rb, re) into the wall batch (geometry as in
  /// wallContactsOfParticle) and clears history and force of all entries (the touching ones get
  /// theirs back in scatterWalls). False if the run has more entries than a batch holds.
  template <bool AllPlanes>
  bool gatherWalls(std::size_t rb, std::size_t re) {
    WallBatch& b = *wallBatch;
    const std::uint32_t base = wallRowStart[rb], count = wallRowStart[re] - base;
    b.size = 0;
    b.uniform = true;
    if (count > WallBatch::kCapacity) return false;
    if (count == 0) return true;
    WallContactList& list = *wallList;
    // The particle of each entry comes with the list (most rows have no wall entry: no per-row work).
    const std::uint32_t* const particleOf = list.particle.data() + base;
    const std::uint32_t runStart = static_cast<std::uint32_t>(rb);
    const WallPrimitive* const primitives = walls->primitives->data();
    const std::uint32_t* const primitiveOf = list.primitive.data() + base;
    Vec3* const h = list.tangentialHistory.data() + base;
    Vec3* const rh = R == RollingLaw::Epsd ? list.rollingHistory.data() + base : nullptr;
    Vec3* const listForce = list.force.data() + base;
    std::uint32_t m = 0;
    for (std::uint32_t c = 0; c < count; ++c) {
      const std::uint32_t row = particleOf[c] - runStart;
      const std::size_t i = rb + row;
      const WallPrimitive& prim = primitives[primitiveOf[c]];
      const Vec3 xi = position[i];
      // (planes: distanceToPrimitive's plane case inline, no dispatch on the kind)
      const WallDistance wd = !prim.active ? WallDistance{1e300, {}}
                              : AllPlanes  ? WallDistance{dot(xi - prim.a, prim.b), prim.b}
                                           : distanceToPrimitive(prim, xi);
      const double ri = radius[i & attribute];
      const Vec3 contactPoint = xi - wd.distance * wd.normal;
      b.entry[m] = base + c;
      b.row[m] = row;
      b.pairIndex[m] = static_cast<std::uint32_t>(prim.wall);  // the wall until the second pass
      b.nx[m] = wd.normal.x;
      b.ny[m] = wd.normal.y;
      b.nz[m] = wd.normal.z;
      b.overlap[m] = ri - wd.distance;
      b.px[m] = contactPoint.x;
      b.py[m] = contactPoint.y;
      b.pz[m] = contactPoint.z;
      const Vec3 hk = h[c];
      b.hx[m] = hk.x;
      b.hy[m] = hk.y;
      b.hz[m] = hk.z;
      h[c] = Vec3{};
      if constexpr (R == RollingLaw::Epsd) {
        const Vec3 r = rh[c];
        b.rhx[m] = r.x;
        b.rhy[m] = r.y;
        b.rhz[m] = r.z;
        rh[c] = Vec3{};
      }
      listForce[c] = Vec3{};
      m += !(wd.distance >= ri) ? 1u : 0u;  // touching: keep the entry
    }
    const Vec3* const wallVelocity = walls->velocity->data();
    const Vec3* const wallAngularVelocity = walls->angularVelocity->data();
    const Vec3* const wallCentre = walls->centre->data();
    const int* const wallMaterial = walls->material->data();
    bool uniform = true;
    std::uint32_t firstPair = 0;
    for (std::uint32_t e = 0; e < m; ++e) {
      const std::size_t i = rb + b.row[e];
      const std::uint32_t w = b.pairIndex[e];
      const Vec3 n = loadLane(b.nx, b.ny, b.nz, e);
      const Vec3 contactPoint = loadLane(b.px, b.py, b.pz, e);
      const Vec3 ww = wallAngularVelocity[w];
      const Vec3 wallPointVelocity = wallVelocity[w] + cross(ww, contactPoint - wallCentre[w]);
      const Vec3 vi = velocity[i], wi = angularVelocity[i];
      const std::size_t ia = i & attribute;
      const double ri = radius[ia], mi = mass[ia];
      const Vec3 relativeVelocity = vi - ri * cross(wi, n) - wallPointVelocity;
      storeLane(b.vx, b.vy, b.vz, e, relativeVelocity);
      if constexpr (R != RollingLaw::None) {
        const Vec3 dw = wi - ww;
        storeLane(b.wx, b.wy, b.wz, e, dw);
      }
      b.ri[e] = ri;
      b.mi[e] = mi;
      if constexpr (R == RollingLaw::Epsd) b.inertia[e] = 1.4 * mi * ri * ri;
      const std::uint32_t pair = static_cast<std::uint32_t>(type[ia]) * types + static_cast<std::uint32_t>(wallMaterial[w]);
      b.pairIndex[e] = pair;
      if (e == 0) firstPair = pair;
      uniform = uniform && pair == firstPair;
    }
    b.uniform = uniform;
    b.size = m;
    return true;
  }

  /// Adds the evaluated wall contacts in list order to their particles and records them.
  template <bool Logs>
  [[gnu::always_inline]] void scatterWalls(std::size_t rb) {
    const WallBatch& b = *wallBatch;
    WallContactList& list = *wallList;
    Vec3* const h = list.tangentialHistory.data();
    Vec3* const rh = list.rollingHistory.data();
    Vec3* const listForce = list.force.data();
    Vec3* const listPoint = list.point.data();
    for (std::uint32_t e = 0; e < b.size; ++e) {
      const std::size_t i = rb + b.row[e];
      const std::uint32_t k = b.entry[e];
      const Vec3 f = loadLane(b.fx, b.fy, b.fz, e);
      addToRow<Logs>(i, f, Vec3{b.tx[e], b.ty[e], b.tz[e]});
      listForce[k] = f;
      listPoint[k] = {b.px[e], b.py[e], b.pz[e]};
      h[k] = {b.hx[e], b.hy[e], b.hz[e]};
      if constexpr (R == RollingLaw::Epsd) rh[k] = {b.rhx[e], b.rhy[e], b.rhz[e]};
    }
  }

  /// Completes a run of rows [rb, re) whose pairs were all scattered: each row's sum and walls.
  /// Batched walls: sums of all rows, then the wall contacts (each touches only its own
  /// particle: the same order of additions per particle as row by row).
  template <bool Logs>
  [[gnu::always_inline]] void finishRun(std::size_t rb, std::size_t re, bool wallsGathered) {
    const ContactBatch& b = *batch;
    if (!wallsGathered) {
      for (std::size_t i = rb; i < re; ++i) finishRow<Logs>(i, b.rowForce[i - rb], b.rowTorque[i - rb]);
      return;
    }
    for (std::size_t i = rb; i < re; ++i)
      if (rowStart[i] < rowStart[i + 1]) addToRow<Logs>(i, b.rowForce[i - rb], b.rowTorque[i - rb]);
    scatterWalls<Logs>(rb);
  }

  /// The rows [rb, re) (candidates [base, base + count), count <= capacity): owners, gather,
  /// evaluation, body forces up to the last partner, scatter, completion. The additions to each
  /// force happen in the same order as one row and one contact at a time.
  template <bool Logs>
  void processRun(std::size_t rb, std::size_t re, std::uint32_t maxPartner) {
    ContactBatch& b = *batch;
    const std::uint32_t base = rowStart[rb], count = rowStart[re] - base;
    // The run's tangential history (24 B per candidate, read for the touching pairs after the
    // distance test): requested now, so that the lines arrive while the candidates are tested.
    prefetchEntries(history, base, count);
    // Likewise the run's wall entries (history read; force and contact point written).
    if (batchWalls) {
      const std::uint32_t wallBase = wallRowStart[rb], wallCount = wallRowStart[re] - wallBase;
      WallContactList& list = *wallList;
      for (const Vec3* array : {list.tangentialHistory.data(), list.force.data(), list.point.data()})
        prefetchEntries(array, wallBase, wallCount);
    }
    // Owner of each candidate: kRowFill stores per row without a loop (the next row overwrites
    // the excess); longer rows finish in a loop.
    for (std::size_t i = rb; i < re; ++i) {
      const std::uint32_t from = rowStart[i] - base, length = rowStart[i + 1] - rowStart[i];
      const std::uint32_t row = static_cast<std::uint32_t>(i - rb);
      for (std::uint32_t q = 0; q < ContactBatch::kRowFill; ++q) b.owner[from + q] = row;
      for (std::uint32_t q = ContactBatch::kRowFill; q < length; ++q) b.owner[from + q] = row;
    }
    b.size = 0;
    b.uniform = true;
    gatherRun(rb, base, count, 0);
    evaluateBatch<N, R, C>(b, coefficients, dt);
    const bool wallsGathered =
        batchWalls && (walls->allPlanes ? gatherWalls<true>(rb, re) : gatherWalls<false>(rb, re));
    if (wallsGathered) evaluateWallBatch<N, R, C>(*wallBatch, coefficients, dt);
    initialiseUpTo(std::min<std::size_t>(end, std::max<std::size_t>(re, std::size_t{maxPartner} + 1)));
    for (std::size_t r = 0; r < re - rb; ++r) b.rowForce[r] = b.rowTorque[r] = Vec3{};
    scatterRun<Logs>();
    finishRun<Logs>(rb, re, wallsGathered);
  }

  /// A row longer than a batch (a large particle among small ones): evaluated in pieces.
  template <bool Logs>
  void processLongRow(std::size_t i) {
    ContactBatch& b = *batch;
    const std::uint32_t first = rowStart[i], last = rowStart[i + 1];
    constexpr std::uint32_t capacity = ContactBatch::kCapacity;
    initialiseUpTo(std::min<std::size_t>(end, std::size_t{partner[last - 1]} + 1));
    b.rowForce[0] = b.rowTorque[0] = Vec3{};
    for (std::uint32_t q = 0; q < capacity; ++q) b.owner[q] = 0;
    for (std::uint32_t from = first; from < last; from += capacity) {
      b.size = 0;
      b.uniform = true;
      gatherRun(i, from, std::min(last - from, capacity), 0);
      evaluateBatch<N, R, C>(b, coefficients, dt);
      scatterRun<Logs>();
    }
    finishRun<Logs>(i, i + 1, false);
  }

  void run() {
    // A team of one logs nothing (no later blocks, no receiving rows): its loops are compiled
    // without the logging calls. Present but never taken, those calls made the settled bed ~2.5 %
    // slower on one thread (probably: a call may write any memory, so the loops reload more).
    if (!laterBlocks && !receiving) {
      if (end - begin >= kPrefetchFromRows) runRows<true, false, false>();
      else runRows<false, false, false>();
    } else if (end - begin >= kPrefetchFromRows) runRows<true, false, true>();
    else if (laterBlocks) runRows<false, true, true>();
    else runRows<false, false, true>();
  }

  /// Rows in runs of at most kCapacity candidates and kCapacity rows.
  template <bool Prefetch, bool PrefetchLaterBlock, bool Logs>
  void runRows() {
    constexpr std::uint32_t capacity = ContactBatch::kCapacity;
    std::size_t i = begin;
    while (i < end) {
      const std::uint32_t base = rowStart[i];
      const std::uint32_t length = rowStart[i + 1] - base;
      if constexpr (Prefetch) prefetchFarPartners(i + kPrefetchRows);
      if constexpr (PrefetchLaterBlock) prefetchLaterBlockPartners(i + kPrefetchRows);
      if (length == 0) {
        if (withWalls && wallRowStart[i] != wallRowStart[i + 1]) {
          // No neighbours but wall entries: complete the row at once.
          initialiseUpTo(i + 1);
          finishRow<Logs>(i, Vec3{}, Vec3{});
          ++i;
          continue;
        }
        // Free flight: the rows [i, k) have no partners and no wall entries. Their forces are
        // complete once initialised (half list: contributions to a row come from rows <= it, and
        // the rows between are empty), so the body forces run as one plain loop over the
        // stretch instead of the row-by-row completion (same operations per particle).
        std::size_t k = i + 1;
        const std::uint32_t wallBase = withWalls ? wallRowStart[i] : 0;
        while (k < end && rowStart[k + 1] == base && (!withWalls || wallRowStart[k + 1] == wallBase)) {
          if constexpr (Prefetch) prefetchFarPartners(k + kPrefetchRows);
          if constexpr (PrefetchLaterBlock) prefetchLaterBlockPartners(k + kPrefetchRows);
          ++k;
        }
        initialiseUpTo(k);
        i = k;
        continue;
      }
      if (length > capacity) {
        processLongRow<Logs>(i);
        ++i;
        continue;
      }
      std::uint32_t maxPartner = partner[base + length - 1];
      std::size_t re = i + 1;
      while (re < end && re - i < capacity && rowStart[re + 1] - base <= capacity) {
        if constexpr (Prefetch) prefetchFarPartners(re + kPrefetchRows);
        if constexpr (PrefetchLaterBlock) prefetchLaterBlockPartners(re + kPrefetchRows);
        // An empty row's "last entry" is the previous row's: the maximum is unchanged.
        maxPartner = std::max(maxPartner, partner[rowStart[re + 1] - 1]);
        ++re;
      }
      processRun<Logs>(i, re, maxPartner);
      i = re;
    }
    initialiseUpTo(end);
  }
};

}  // namespace gf::dem
