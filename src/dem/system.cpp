#include "dem/system.hpp"
#include "dem/walls/wall_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/cpu_features.hpp"
#include "core/parallel.hpp"

namespace gf::dem {

System::System(Params& root, const Domain& domain, const Vec3& gravity, InitialParticles initial,
               const parallel::Decomposition& decomposition)
    : domain_(domain),
      decomposition_(decomposition),
      distributed_(decomposition.distributed()),
      box_(domain),
      gravity_(gravity),
      table_(root) {
  readWalls(root);
  InsertionCommon::table() = &table_;
  for (Params& ins : root.list({"insertion", "-", "particle insertion (initial and rate-based)"})) {
    inserters_.push_back(Registry<Inserter>::instance().create(ins, {"type", "-", "insertion method"}));
    // a particle's coarse-graining factor is its material's (coarseGrainingByMaterial)
    const Inserter& made = *inserters_.back();
    for (std::size_t i = 0; i + 1 < inserters_.size() && !root.documenting(); ++i)
      if (inserters_[i]->material() == made.material() && inserters_[i]->coarseGraining() != made.coarseGraining())
        ins.fail("coarse_graining",
                 fmt::format("{:g} for material {} of insertion {}, which another insertion makes with {:g}",
                             made.coarseGraining(), table_.materials()[made.material()].name, inserters_.size() - 1,
                             inserters_[i]->coarseGraining()),
                 "the same coarse_graining for every insertion of one material (or a material per factor)");
  }
  for (Params& o : root.list({"outlets", "-", "deletion regions (particles entering are removed)"}))
    outlets_.emplace_back(o);
  Params ns = root.section({"neighbour_search", "-", "Verlet lists on linked cells"});
  neighbour_.skin = ns.real({"skin", "m", "Verlet skin (0: 0.1 x largest diameter)", Range::nonNegative()}, 0.0);
  neighbour_.reorderInterval = static_cast<int>(ns.integer(
      {"reorder_interval", "-", "Morton (space-filling curve) reordering every this many rebuilds (0: never)",
       Range::atLeast(0)},
      20));
  Params par = root.section({"parallel", "-", "MPI runs: load balancing among the ranks"});
  balance_.threshold = par.real({"rebalance_threshold", "-",
                                 "re-cut the ranks' boxes when the largest load of a rank exceeds this times the mean: "
                                 "DEM-only cases, the particles it owns (recursive coordinate bisection by Zoltan); "
                                 "cases with a fluid, the measured work of its cells and particles (the cell cuts "
                                 "of each split axis moved, docs/parallel.md)",
                                 Range::atLeast(1.0)},
                                1.2);
  balance_.interval = par.integer(
      {"rebalance_interval", "-",
       "check the balance at the first list build after every this many steps (0: never); cases with a fluid also "
       "check once a tenth of it after the start or restart",
       Range::atLeast(0)},
      1000);
  balance_.byPairs = par.choice({"rebalance_weight", "-",
                                 "load of a particle: particles (1 each) or pairs (1 + its neighbour-list pairs, "
                                 "for beds with dense and dilute parts; DEM-only cases)"},
                                {"particles", "pairs"}, "particles") == "pairs";
  balance_.cellCost = par.real({"rebalance_cell_cost", "-",
                                "cases with a fluid: the work of a fluid cell as a number of particles' work; 0 = "
                                "measured, from the run's time per cell and per particle (the cuts then depend on the "
                                "machine's speeds)",
                                Range::nonNegative()},
                               0.0);
  if (root.documenting()) return;
  updateWalls();
  // A restart skips the initial insertion: load() would discard its particles (a random packing of
  // 150,000 spheres: ~0.1 s of the restart).
  if (initial == InitialParticles::FromCheckpoint) return;
  insertAndRemove(0.0);
  refresh();  // (applies the initial insertion's removals: particles of other ranks, outlets)
  checkBoxesHoldTheReach(root);
}

void System::checkBoxesHoldTheReach(Params& root) const {
  // Ghosts come from the 26 neighbouring boxes only: a box must be at least as wide as the contact
  // reach (largest diameter + skin), or a particle two boxes away could touch one of this box.
  if (!distributed_ || root.documenting()) return;
  const double width = decomposition_.smallestBoxWidth();
  if (width >= ghostReach_) return;
  root.section({"domain"}).fail(
      "decomposition",
      fmt::format("boxes of {:.4g} m ({} ranks as {}), narrower than the contact reach {:.4g} m (largest diameter "
                  "+ skin)",
                  width, decomposition_.ranks(), decomposition_.describe(), ghostReach_),
      fmt::format("a layout whose boxes are at least {:.4g} m wide along every split axis (fewer ranks along the "
                  "narrow axis)",
                  ghostReach_));
}

std::vector<std::uint32_t> System::takePendingOrder() {
  std::vector<std::uint32_t> order;
  if (hasPendingOrder_) {
    hasPendingOrder_ = false;
    order.swap(pendingOrder_);
    return order;
  }
  order.resize(particles_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  return order;
}

void System::readWalls(Params& root) {
  const double reachDefault = norm(domain_.size());
  std::vector<Params> wallEntries = root.list({"walls", "-", "walls (geometry by type, optional prescribed motion)"});
  for (Params& w : wallEntries) {
    auto wall = Registry<Wall>::instance().create(w, {"type", "-", "wall type"});
    const std::string name = w.text({"name", "-", "wall name (for monitors)"}, fmt::format("wall{}", wallNames_.size()));
    const int material =
        table_.readMaterial(w, {"material", "-", "wall material name ('rigid': infinitely stiff, the default)"},
                            kRigidMaterial);
    WallMotion motion;
    motion.velocity = w.vec3({"velocity", "m/s", "translation velocity of the wall"}, {});
    motion.angularVelocity = w.vec3({"angular_velocity", "rad/s", "angular velocity about 'centre'"}, {});
    motion.centre = w.vec3({"centre", "m", "centre of rotation at t = 0 (moves with the wall)"}, {});
    const double activeUntil = w.real({"active_until", "s", "the wall disappears at this time (e.g. an orifice plug)",
                                       Range::nonNegative()},
                                      std::numeric_limits<double>::infinity());
    if (w.documenting()) continue;
    wallActiveUntil_.push_back(activeUntil);
    const int index = static_cast<int>(wallNames_.size());
    wallNames_.push_back(name);
    wallMaterial_.push_back(material);
    wallMotion_.push_back(motion);
    // Geometry moves under the rotation unless every primitive is symmetric about the spin axis
    // through the centre (a drum spinning about its own axis, a plane spinning in itself).
    bool moves = false;
    double reach = 0.0;
    const double spin = norm(motion.angularVelocity);
    const Vec3 spinAxis = spin > 0.0 ? motion.angularVelocity / spin : Vec3{};
    for (WallPrimitive prim : wall->primitives()) {
      prim.wall = index;
      if (spin > 0.0) {
        if (prim.kind == PrimitiveKind::Axisymmetric) {
          const Vec3 offset = motion.centre - prim.a;
          const bool onAxis = norm(offset - dot(offset, prim.b) * prim.b) < 1e-12 * (1.0 + norm(offset));
          moves |= !(norm(cross(prim.b, spinAxis)) < 1e-12 && onAxis);
          reach = std::max({reach, norm(prim.a - motion.centre) + prim.length + std::max(prim.r0, prim.r1)});
        } else if (prim.kind == PrimitiveKind::Plane) {
          moves |= !(norm(cross(prim.b, spinAxis)) < 1e-12);
          reach = std::max(reach, reachDefault + norm(prim.a - motion.centre));
        } else {
          moves = true;
          for (const Vec3& v : {prim.a, prim.b, prim.c}) reach = std::max(reach, norm(v - motion.centre));
        }
      }
      referencePrimitives_.push_back(prim);
    }
    wallGeometryMoves_.push_back(moves);
    wallReach_.push_back(reach);
  }
  std::vector<bool> fixed(wallNames_.size());
  for (std::size_t w = 0; w < fixed.size(); ++w)
    fixed[w] = wallMotion_[w].velocity == Vec3{} && wallMotion_[w].angularVelocity == Vec3{} &&
               std::isinf(wallActiveUntil_[w]);
  checkWallsDoNotOverlap(wallEntries, referencePrimitives_, wallNames_, fixed);
  primitives_ = referencePrimitives_;
  wallVelocity_.resize(wallNames_.size());
  wallAngularVelocity_.resize(wallNames_.size());
  wallCentre_.resize(wallNames_.size());
}

void System::updateWalls() {
  for (std::size_t w = 0; w < wallMotion_.size(); ++w) {
    wallVelocity_[w] = wallMotion_[w].velocity;
    wallAngularVelocity_[w] = wallMotion_[w].angularVelocity;
    wallCentre_[w] = wallMotion_[w].centre + time_ * wallMotion_[w].velocity;
  }
  for (std::size_t k = 0; k < referencePrimitives_.size(); ++k) {
    const WallPrimitive& ref = referencePrimitives_[k];
    primitives_[k].active = time_ < wallActiveUntil_[ref.wall];
    const WallMotion& m = wallMotion_[ref.wall];
    if (m.velocity == Vec3{} && m.angularVelocity == Vec3{}) continue;
    const Vec3 theta = time_ * m.angularVelocity;
    const Vec3 c = wallCentre_[ref.wall];
    auto movePoint = [&](const Vec3& x) { return c + rotate(x - m.centre, theta); };
    WallPrimitive& cur = primitives_[k];
    cur.a = movePoint(ref.a);
    if (ref.kind == PrimitiveKind::Triangle) {
      cur.b = movePoint(ref.b);
      cur.c = movePoint(ref.c);
    } else {
      cur.b = rotate(ref.b, theta);  // normal or axis
    }
  }
}

bool System::insertAndRemove(double dt) {
  ParticleSet& p = particles_;
  const std::size_t before = p.size();
  // Existing particles for the inserters' overlap checks: the set's own on one rank; under MPI
  // those every rank owns, plus the ones inserted earlier in this call (the same on every rank).
  // (captures two words: the std::function keeps them in place, no allocation every step)
  auto addExisting = [this, before](const std::function<bool(const Vec3&)>& near, OverlapGrid& grid) {
    const ParticleSet& p = particles_;
    if (!distributed_) {
      for (std::size_t i = 0; i < p.size(); ++i)
        if (near(p.position[i])) grid.add(p.position[i], p.radius[i]);
      return;
    }
    parallel::Bytes mine;
    parallel::Packer out(mine);
    for (std::size_t i = 0; i < before; ++i)
      if (!p.isGhost(i) && near(p.position[i])) {
        out.put(p.position[i]);
        out.put(p.radius[i]);
      }
    for (const parallel::Bytes& bytes : parallel::allgather(mine)) {
      parallel::Unpacker in(bytes);
      while (!in.done()) {
        const Vec3 x = in.get<Vec3>();
        grid.add(x, in.get<double>());
      }
    }
    for (std::size_t i = before; i < p.size(); ++i)
      if (near(p.position[i])) grid.add(p.position[i], p.radius[i]);
  };
  InsertionContext ctx{p, nextId_, domain_, addExisting};
  bool changed = false;
  for (auto& ins : inserters_) changed |= ins->insert(ctx, time_, dt) > 0;
  if (distributed_ && p.ghost.size() != p.size()) p.ghost.resize(p.size(), 0);
  hasPendingOrder_ = false;
  pendingOrder_.clear();
  if (outlets_.empty() && !(distributed_ && p.size() > before)) return changed;  // (no pass over the particles)
  // Every rank inserted the same particles; under MPI each keeps those in its box. Outlets remove
  // the particles whose centre is inside a deletion box (each rank its own).
  std::vector<std::uint32_t> keep;
  bool removed = false;
  keep.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (distributed_ && i >= before && decomposition_.ownerOf(p.position[i]) != decomposition_.rank()) {
      removed = true;  // another rank's new particle
      continue;
    }
    bool inside = false;
    if (!p.isGhost(i))
      for (Outlet& o : outlets_)
        if (o.contains(p.position[i])) {
          o.removedMass += p.mass[i];
          ++o.removedCount;
          inside = true;
          break;
        }
    if (inside) removed = true;
    else keep.push_back(static_cast<std::uint32_t>(i));
  }
  hasPendingOrder_ = removed;
  if (removed) {
    // Applied by the rebuild that follows (removal, like insertion, makes one).
    pendingOrder_ = std::move(keep);
    return true;
  }
  return changed;
}

void System::refresh() {
  rebuild(takePendingOrder(), list_.rows());
  updateInverseInertia();
  computeForces(0.0, 0.0);
}

bool System::needsRebuild(double largestMove, double secondLargestMove) const {
  if (list_.rows() != particles_.size() || positionAtBuild_.size() != particles_.size()) return true;
  double wallMove = 0.0;
  const double elapsed = time_ - timeAtBuild_;
  for (std::size_t w = 0; w < wallMotion_.size(); ++w)
    wallMove = std::max(wallMove, elapsed * (norm(wallMotion_[w].velocity) +
                                             (wallGeometryMoves_[w] ? norm(wallMotion_[w].angularVelocity) * wallReach_[w]
                                                                    : 0.0)));
  // A pair that was not listed was at least r_i + r_j + skin apart; since then it came closer by at
  // most |dx_i| + |dx_j| <= largest + second largest displacement (of two different particles), so the
  // list stays complete while that sum is within the skin. Walls: particle plus wall movement.
  return largestMove + secondLargestMove > skin_ || largestMove + wallMove > skin_;
}

void System::rebuild(std::vector<std::uint32_t> order, std::size_t listedRows) {
  ScopedPhase timer(timers_, Phase::NeighbourSearch);
  ParticleSet& p = particles_;
  if (distributed_ && p.ghost.size() != p.size()) p.ghost.resize(p.size(), 0);
  double maxDiameter = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!p.isGhost(i)) maxDiameter = std::max(maxDiameter, 2.0 * p.radius[i]);
  if (distributed_) maxDiameter = parallel::maxOverRanks(maxDiameter);
  skin_ = neighbour_.skin > 0.0 ? neighbour_.skin : 0.1 * maxDiameter;
  // Periodic Morton reordering for cache locality: the particles get the code of their cell as
  // their order key, and the arrays follow (orderKey, id) (ParticleSet::orderKey).
  const bool reorder = neighbour_.reorderInterval > 0 && rebuilds_ % neighbour_.reorderInterval == 0;
  const double mortonCell = maxDiameter + skin_;
  std::vector<std::int64_t> previous;
  bool identity = false;  // no particle moved in the arrays, none came or went
  if (distributed_) migrateAndExchangeGhosts(order, reorder, mortonCell, maxDiameter + skin_, previous, listedRows);
  else identity = orderLocally(order, reorder, mortonCell, previous, listedRows);
  const bool rollingHistory = table_.rollingLaw() == RollingLaw::Epsd;
  list_.build(p, box_, domain_.min, domain_.max, skin_, previous, rollingHistory);
  wallList_.build(p, primitives_, skin_, previous, rollingHistory);
  if (distributed_) setHistoriesFromRecords(arrivedPairs_, arrivedWalls_, arrived_);
  positionAtBuild_ = p.position;
  timeAtBuild_ = time_;
  ++rebuilds_;
  // 1/m and 1/I follow the particles; unchanged when none moved in the arrays, none came or went
  // (refresh() recomputes them in any case: its caller may have edited masses)
  if (!identity || inverseMass_.size() != p.size()) updateInverseInertia();
}


void System::assignMortonKeys(const std::vector<std::uint32_t>& subset, double mortonCell) {
  ParticleSet& p = particles_;
  parallelFor(static_cast<std::int64_t>(subset.size()), [&](std::int64_t k) {
    const std::uint32_t i = subset[k];
    p.orderKey[i] = mortonCode(p.position[i], domain_.min, mortonCell);
  });
}

bool System::orderLocally(std::vector<std::uint32_t>& order, bool reorder, double mortonCell,
                          std::vector<std::int64_t>& previous, std::size_t listedRows) {
  ParticleSet& p = particles_;
  if (reorder && !order.empty()) assignMortonKeys(order, mortonCell);
  sortByKeyThenId(order, p);
  bool identity = order.size() == p.size();
  for (std::size_t k = 0; identity && k < order.size(); ++k) identity = order[k] == k;
  if (!identity) p.gather(order);
  previous.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) previous[k] = order[k] < listedRows ? order[k] : -1;
  return identity;
}

const std::vector<std::size_t>& System::threadBlocks() {
  // (lists of other particles, before a rebuild: no split, the callers fall back to equal blocks)
  const std::size_t n = particles_.size();
  if (list_.rows() != n || (!primitives_.empty() && wallList_.rowStart.size() != n + 1)) threadBlocks_.clear();
  else splitRowsAmongThreads(list_, wallList_, !primitives_.empty(), n, omp_get_max_threads(), threadBlocks_);
  return threadBlocks_;
}

void System::setThreadSpeeds(const std::vector<double>& speeds) {
  buffers_.adaptive = speeds.empty();
  buffers_.speed = speeds;
  buffers_.splitOfList = ~std::uint64_t{0};  // a new split at the next force evaluation
}

void System::updateInverseInertia() {
  const ParticleSet& p = particles_;
  inverseMass_.resize(p.size());
  inverseMoment_.resize(p.size());
  parallelFor(static_cast<std::int64_t>(p.size()), [&](std::int64_t i) {
    inverseMass_[i] = 1.0 / p.mass[i];
    inverseMoment_[i] = 1.0 / p.inertia(i);  // solid sphere, 2/5 m r^2
  });
  // Radius, mass and type change only with the particle set (insertion, removal, refresh()), as do
  // 1/m and 1/I: checked here, with them.
  identicalSpheres_ = !p.radius.empty();
  for (std::size_t i = 1; identicalSpheres_ && i < p.size(); ++i)
    identicalSpheres_ = p.radius[i] == p.radius[0] && p.mass[i] == p.mass[0] && p.type[i] == p.type[0];
}

void System::computeForces(double dt, double halfKick) {
  ScopedPhase timer(timers_, Phase::Contacts);
  bool hasTriangles = false, allPlanes = true;
  for (const WallPrimitive& w : primitives_) {
    hasTriangles |= w.kind == PrimitiveKind::Triangle;
    allPlanes &= w.kind == PrimitiveKind::Plane;
  }
  const WallState walls{&primitives_, &wallMaterial_, &wallVelocity_, &wallAngularVelocity_, &wallCentre_,
                        hasTriangles, allPlanes};
  dispatchLaws(table_.normalLaw(), table_.rollingLaw(), table_.cohesionLaw(),
               [&]<NormalLaw N, RollingLaw R, CohesionLaw C>() {
                 contactForces<N, R, C>(particles_, list_, wallList_, walls, table_, box_, gravity_, dt,
                                        identicalSpheres(), buffers_);
               });
  if (halfKick == 0.0) return;
  // The closing half kick, once every force is final (each thread its block of the force split).
  closingHalfKick(particles_, halfKick, {inverseMass_.data(), inverseMoment_.data(), identicalSpheres()},
                  buffers_.blockStart);
}

namespace {
// The two largest values of a set (order-independent, so the OpenMP reduction is deterministic).
struct LargestTwo {
  double first = 0.0, second = 0.0;
  void add(double value) {  // branch-free: the new second is the larger of the old second and
    second = std::max(second, std::min(first, value));  // the smaller of (old first, value)
    first = std::max(first, value);
  }
  void merge(const LargestTwo& other) {
    add(other.first);
    add(other.second);
  }
};
#pragma omp declare reduction(largestTwo : LargestTwo : omp_out.merge(omp_in)) initializer(omp_priv = LargestTwo{})

/// Opening half kick and drift of the particles [begin, end) (velocity Verlet), with the two
/// largest squared displacements since the last list build. One instantiation per box kind and
/// tracking state, raw restrict pointers in locals: the branches and the pointer reloads (the
/// stores could alias the captured pointers) leave the loop. Same arithmetic per particle as
/// before; the largest two are order-independent (exact max/min).
struct DriftArrays {
  Vec3* __restrict position;
  Vec3* __restrict velocity;
  Vec3* __restrict angularVelocity;
  const Vec3* __restrict force;
  const Vec3* __restrict torque;
  const Vec3* __restrict positionAtBuild;
  const double* __restrict inverseMass;
  const double* __restrict inverseMoment;
  std::size_t attribute;  // index mask of 1/m and 1/I (identicalIndexMask, block_sweep.hpp)
};

/// Particles ahead of the one being moved whose lines the team's integration requests for
/// writing (SharedLines).
constexpr std::int64_t kOwnAhead = 24;

template <bool Periodic, bool Tracked, bool SharedLines>
void kickAndDrift(const DriftArrays& a, const PeriodicBox& box, double dt, std::int64_t begin, std::int64_t end,
                  LargestTwo& largest) {
  Vec3* __restrict x = a.position;
  Vec3* __restrict v = a.velocity;
  Vec3* __restrict w = a.angularVelocity;
  const Vec3* __restrict f = a.force;
  const Vec3* __restrict tq = a.torque;
  const Vec3* __restrict x0 = a.positionAtBuild;
  const double* __restrict inverseMass = a.inverseMass;
  const double* __restrict inverseMoment = a.inverseMoment;
  const double halfDt = 0.5 * dt;
  const PeriodicBox localBox = box;
  const std::size_t at = a.attribute;
  LargestTwo local = largest;  // (in registers, not through the reference)
  for (std::int64_t i = begin; i < end; ++i) {
    if constexpr (SharedLines) {
      // A block after the first: the particles near the blocks' boundary are partners of the
      // earlier blocks' rows, whose threads read their position and velocities in the contact
      // sweep; a store to such a line waits for the other core's copy to be invalidated unless the
      // line was requested for writing (per particle on 2 threads: 10-19 ns in the first eighth
      // of the second block, 4-5 ns elsewhere, before; 5-7 ns with the requests).
      if (i + kOwnAhead < end) {
        prefetchForWrite(x + i + kOwnAhead);
        prefetchForWrite(v + i + kOwnAhead);
        prefetchForWrite(w + i + kOwnAhead);
      }
    }
    const auto ia = static_cast<std::size_t>(i) & at;
    const Vec3 vi = v[i] + (halfDt * inverseMass[ia]) * f[i];
    v[i] = vi;
    w[i] += (halfDt * inverseMoment[ia]) * tq[i];
    const Vec3 xi = Periodic ? localBox.wrap(x[i] + dt * vi) : x[i] + dt * vi;
    x[i] = xi;
    if constexpr (Tracked) local.add(normSquared(Periodic ? localBox.minimumImage(xi - x0[i]) : xi - x0[i]));
  }
  largest = local;
}

void kickAndDriftRange(const DriftArrays& a, const PeriodicBox& box, bool tracked, bool sharedLines, double dt,
                       std::int64_t begin, std::int64_t end, LargestTwo& largest) {
  auto run = [&]<bool Shared>() {
    if (box.anyPeriodic) {
      if (tracked) kickAndDrift<true, true, Shared>(a, box, dt, begin, end, largest);
      else kickAndDrift<true, false, Shared>(a, box, dt, begin, end, largest);
    } else {
      if (tracked) kickAndDrift<false, true, Shared>(a, box, dt, begin, end, largest);
      else kickAndDrift<false, false, Shared>(a, box, dt, begin, end, largest);
    }
  };
  if (sharedLines && cpuHasPrefetchW()) run.template operator()<true>();
  else run.template operator()<false>();
}
}  // namespace

void System::step(double dt) {
  ParticleSet& p = particles_;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  LargestTwo displacement2;  // squared displacements since the last list build
  {
    // Velocity Verlet (translation and rotation of spheres): half kick with old forces, drift;
    // the two largest displacements since the last list build come with the drift.
    ScopedPhase timer(timers_, Phase::Integration);
    const bool tracked = positionAtBuild_.size() == p.size();
    const DriftArrays arrays{p.position.data(),        p.velocity.data(),      p.angularVelocity.data(),
                             p.force.data(),           p.torque.data(),        positionAtBuild_.data(),
                             inverseMass_.data(),      inverseMoment_.data(),
                             identicalIndexMask(identicalSpheres())};
    // With a team, each thread takes the block of rows it swept in the last force evaluation (its
    // particles are in its cache); the reduction is order-independent, so any split gives the
    // same result.
    const std::vector<std::size_t>& blocks = buffers_.blockStart;
    const int threads = omp_get_max_threads();
    if (threads <= 1) {
      kickAndDriftRange(arrays, box_, tracked, false, dt, 0, n, displacement2);
    } else if (blocks.size() == static_cast<std::size_t>(threads) + 1 && blocks.back() == static_cast<std::size_t>(n)) {
#pragma omp parallel num_threads(threads) reduction(largestTwo : displacement2)
      {
        const int t = omp_get_thread_num();
        const bool own = omp_get_num_threads() == threads;
        const auto begin = static_cast<std::int64_t>(own ? blocks[t] : 0);
        const auto end = own ? static_cast<std::int64_t>(blocks[t + 1]) : (t == 0 ? n : 0);
        kickAndDriftRange(arrays, box_, tracked, own && t > 0, dt, begin, end, displacement2);
      }
    } else {
#pragma omp parallel reduction(largestTwo : displacement2)
      {
        const auto [begin, end] = threadBlock(n, omp_get_thread_num(), omp_get_num_threads(), nullptr);
        kickAndDriftRange(arrays, box_, tracked, false, dt, begin, end, displacement2);
      }
    }
  }
  time_ += dt;
  updateWalls();
  const std::size_t before = p.size();
  bool rebuildNow = insertAndRemove(dt);
  if (distributed_) {
    // One vote for all ranks (the same rebuild steps as on one rank): the displacements of the
    // particles every rank owns, and whether any rank's particles came or went.
    ScopedPhase timer(timers_, Phase::Communication);
    rebuildNow = voteForRebuild(rebuildNow);
  } else {
    rebuildNow = rebuildNow || needsRebuild(std::sqrt(displacement2.first), std::sqrt(displacement2.second));
  }
  if (rebuildNow) {
    rebuild(takePendingOrder(), std::min(before, list_.rows()));
  } else if (distributed_) {
    ScopedPhase timer(timers_, Phase::Communication);
    forwardGhosts();
  }
  computeForces(dt, 0.5 * dt);  // and the closing half kick
  ++steps_;
}

double System::rayleighTime() const {
  double tMin = std::numeric_limits<double>::infinity();
  const auto& mats = table_.materials();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Material& m = mats[particles_.type[i]];
    tMin = std::min(tMin, dem::rayleighTime(particles_.radius[i], m.density, m.youngsModulus, m.poissonRatio));
  }
  // and of the smallest sphere each insertion of the case can make: a rate-based insertion is checked
  // before its first particle, a restart before load() brings the particles
  for (const auto& ins : inserters_) {
    const SmallestInserted s = ins->smallest();
    if (s.material < 0) continue;
    const Material& m = mats[s.material];
    tMin = std::min(tMin, dem::rayleighTime(0.5 * s.diameter, m.density, m.youngsModulus, m.poissonRatio));
  }
  return tMin;
}

std::vector<double> System::coarseGrainingByMaterial() const {
  std::vector<double> factors(table_.materials().size(), 0.0);
  for (const auto& ins : inserters_)
    if (ins->material() >= 0 && ins->coarseGraining() > 0.0)
      factors[static_cast<std::size_t>(ins->material())] = ins->coarseGraining();
  return factors;
}

TimeStepStatus System::checkTimeStep(double dt) const { return dem::checkTimeStep(dt, rayleighTime()); }

void System::checkHealth(long long step, double time) const {
  const ParticleSet& p = particles_;
  enum Problem : int { None, NotFinite, Outside };
  auto kindOf = [&](std::size_t i) {
    if (!isFinite(p.position[i]) || !isFinite(p.velocity[i]) || !isFinite(p.angularVelocity[i])) return NotFinite;
    for (int a = 0; a < 3; ++a)
      if (!domain_.periodic[a] && (p.position[i][a] < domain_.min[a] || p.position[i][a] > domain_.max[a])) return Outside;
    return None;
  };
  auto problemOf = [&](std::size_t i) { return p.isGhost(i) ? None : kindOf(i); };  // (a ghost's owner checks it)
  // The first unhealthy particle (lowest index: the same report on any thread count), found by
  // the team (a pass over all particles, on the main thread's path between DEM steps otherwise).
  const auto n = static_cast<std::int64_t>(p.size());
  std::int64_t first = n;
  // Under MPI first one pass over every particle, ghosts included (a ghost is a copy: unhealthy
  // only if its owner is), without the ghost test; the search that skips ghosts only if it finds
  // something.
  bool suspect = !distributed_;
  for (std::int64_t i = 0; distributed_ && i < n && !suspect; ++i) suspect = kindOf(static_cast<std::size_t>(i)) != None;
  if (!suspect) {
    // (nothing on this rank)
  } else if (runsOnCallingThread(n)) {
    for (std::int64_t i = 0; i < n && first == n; ++i)
      if (problemOf(static_cast<std::size_t>(i)) != None) first = i;
  } else {
#pragma omp parallel for schedule(static) reduction(min : first)
    for (std::int64_t i = 0; i < n; ++i)
      if (i < first && problemOf(static_cast<std::size_t>(i)) != None) first = i;
  }
  // Under MPI every rank learns whether any rank found one, and all report the one of the lowest
  // rank, so that every rank stops with the same message.
  int problem = first == n ? None : problemOf(static_cast<std::size_t>(first));
  std::int64_t id = problem ? p.id[static_cast<std::size_t>(first)] : 0;
  Vec3 where = problem ? p.position[static_cast<std::size_t>(first)] : Vec3{};
  std::string rankText;
  if (distributed_) {
    if (!parallel::anyOverRanks(problem != None)) return;
    parallel::Bytes mine;
    parallel::Packer out(mine);
    out.put(problem);
    out.put(id);
    out.put(where);
    const std::vector<parallel::Bytes> all = parallel::allgather(mine);
    for (std::size_t r = 0; r < all.size(); ++r) {
      parallel::Unpacker in(all[r]);
      problem = in.get<int>();
      id = in.get<std::int64_t>();
      where = in.get<Vec3>();
      if (problem != None) {
        rankText = fmt::format(" on rank {}", r);
        break;
      }
    }
  }
  if (problem == None) return;
  if (problem == NotFinite)
    throw DivergenceError(step, time, "particle position/velocity is NaN or Inf",
                          fmt::format("particle id {}{}", id, rankText), where, "reduce the time step");
  throw DivergenceError(step, time, "particle left the domain", fmt::format("particle id {}{}", id, rankText), where,
                        "no wall or outlet holds it; check walls, outlets and the time step");
}

std::vector<WallLoad> System::wallLoads() const {
  std::vector<WallLoad> loads(wallNames_.size());
  for (std::size_t w = 0; w < loads.size(); ++w) loads[w].name = wallNames_[w];
  // Serial sum in entry order: deterministic (under MPI each rank its own particles, then a sum
  // over ranks).
  for (std::size_t k = 0; k < wallList_.entries(); ++k) {
    const Vec3& f = wallList_.force[k];
    if (f == Vec3{} || particles_.isGhost(wallList_.particle[k])) continue;
    const int w = primitives_[wallList_.primitive[k]].wall;
    loads[w].force -= f;
    loads[w].torque -= cross(wallList_.point[k] - wallCentre_[w], f);
  }
  if (distributed_) {  // (every wall's force and torque in one collective)
    std::vector<double> sums;
    for (const WallLoad& l : loads)
      for (int a = 0; a < 3; ++a) sums.insert(sums.end(), {l.force[a], l.torque[a]});
    sums = parallel::sumOverRanks(sums);
    for (std::size_t w = 0; w < loads.size(); ++w)
      for (int a = 0; a < 3; ++a) {
        loads[w].force[a] = sums[6 * w + 2 * a];
        loads[w].torque[a] = sums[6 * w + 2 * a + 1];
      }
  }
  return loads;
}

ContactStatistics System::contactStatistics() const {
  ContactStatistics s;
  const ParticleSet& p = particles_;
  // (each pair once over all ranks: by the owner of its row)
  for (std::size_t i = 0; i < list_.rows() && i < p.size(); ++i) {
    if (p.isGhost(i)) continue;
    for (std::uint32_t k = list_.rowStart[i]; k < list_.rowStart[i + 1]; ++k) {
      const std::uint32_t j = list_.partner[k];
      const double overlap = p.radius[i] + p.radius[j] - norm(box_.minimumImage(p.position[i] - p.position[j]));
      if (overlap <= 0.0) continue;
      ++s.particleContacts;
      s.maxOverlapRatio = std::max(s.maxOverlapRatio, overlap / std::min(p.radius[i], p.radius[j]));
    }
    for (std::uint32_t k = wallList_.rowStart[i]; k < wallList_.rowStart[i + 1]; ++k) {
      const WallPrimitive& w = primitives_[wallList_.primitive[k]];
      // Entries without force are not in contact (or mesh duplicates of another triangle's contact).
      const bool carries = wallList_.force[k] != Vec3{};
      const double overlap = w.active && carries ? p.radius[i] - distanceToPrimitive(w, p.position[i]).distance : 0.0;
      if (overlap <= 0.0) continue;
      ++s.wallContacts;
      s.maxOverlapRatio = std::max(s.maxOverlapRatio, overlap / p.radius[i]);
    }
  }
  if (distributed_) {
    s.particleContacts = parallel::sumOverRanks(s.particleContacts);
    s.wallContacts = parallel::sumOverRanks(s.wallContacts);
    s.maxOverlapRatio = parallel::maxOverRanks(s.maxOverlapRatio);
  }
  const long long count = globalParticleCount();
  s.coordinationNumber = count ? 2.0 * static_cast<double>(s.particleContacts) / static_cast<double>(count) : 0.0;
  return s;
}

EnergyBalance System::energy() const {
  EnergyBalance e;
  const ParticleSet& p = particles_;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.isGhost(i)) continue;
    e.translational += 0.5 * p.mass[i] * normSquared(p.velocity[i]);
    e.rotational += 0.5 * p.inertia(i) * normSquared(p.angularVelocity[i]);
    e.gravitational -= p.mass[i] * dot(gravity_, p.position[i]);
  }
  // Elastic energy of the normal springs: Hertz 2/5 k d^(5/2), Hooke 1/2 k d^2.
  auto stored = [&](const PairCoefficients& c, double effectiveRadius, double overlap) {
    if (table_.normalLaw() == NormalLaw::Hooke) return 0.5 * c.normalStiffness * overlap * overlap;
    return 0.4 * hertz::stiffnessPrefactor(c.effectiveYoungs, effectiveRadius) * overlap * overlap * std::sqrt(overlap);
  };
  for (std::size_t i = 0; i < list_.rows() && i < p.size(); ++i) {
    if (p.isGhost(i)) continue;
    for (std::uint32_t k = list_.rowStart[i]; k < list_.rowStart[i + 1]; ++k) {
      const std::uint32_t j = list_.partner[k];
      const double overlap = p.radius[i] + p.radius[j] - norm(box_.minimumImage(p.position[i] - p.position[j]));
      if (overlap > 0.0)
        e.elastic += stored(table_.pair(p.type[i], p.type[j]), p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]),
                            overlap);
    }
    for (std::uint32_t k = wallList_.rowStart[i]; k < wallList_.rowStart[i + 1]; ++k) {
      const WallPrimitive& w = primitives_[wallList_.primitive[k]];
      const bool carries = wallList_.force[k] != Vec3{};  // mesh duplicates carry no force
      const double overlap = w.active && carries ? p.radius[i] - distanceToPrimitive(w, p.position[i]).distance : 0.0;
      if (overlap > 0.0) e.elastic += stored(table_.pair(p.type[i], wallMaterial_[w.wall]), p.radius[i], overlap);
    }
  }
  if (distributed_) {
    const std::vector<double> sums =
        parallel::sumOverRanks(std::vector<double>{e.translational, e.rotational, e.gravitational, e.elastic});
    e.translational = sums[0], e.rotational = sums[1], e.gravitational = sums[2], e.elastic = sums[3];
  }
  return e;
}

std::size_t System::memoryBytes() const {
  const ParticleSet& p = particles_;
  std::size_t bytes = p.id.capacity() * 8 + p.type.capacity() * 4 + p.radius.capacity() * 8 + p.mass.capacity() * 8 +
                      (p.position.capacity() + p.velocity.capacity() + p.angularVelocity.capacity() +
                       p.force.capacity() + p.torque.capacity() + p.externalForce.capacity() +
                       p.externalTorque.capacity() + positionAtBuild_.capacity()) *
                          sizeof(Vec3);
  bytes += list_.memoryBytes();
  bytes += wallList_.rowStart.capacity() * 4 + wallList_.primitive.capacity() * 4 + wallList_.particle.capacity() * 4 +
           (wallList_.tangentialHistory.capacity() + wallList_.rollingHistory.capacity() +
            wallList_.force.capacity() + wallList_.point.capacity()) *
               sizeof(Vec3);
  for (const auto& log : buffers_.outgoing) bytes += log.capacity() * sizeof(LoggedContribution);
  for (const auto& log : buffers_.deferred) bytes += log.capacity() * sizeof(LoggedContribution);
  bytes += buffers_.receives.capacity();
  for (const auto& r : buffers_.received) bytes += r.capacity() * sizeof(std::uint32_t);
  bytes += (inverseMass_.capacity() + inverseMoment_.capacity()) * sizeof(double);
  return bytes;
}

}  // namespace gf::dem
