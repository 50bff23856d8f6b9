// The DEM across MPI ranks (System's distributed parts) and the rank-independent checkpoint.
//
// Ownership: a rank owns the particles whose centre lay in its box at the last list build; in
// between they may drift out of it by less than the skin. Ghosts: at every build each rank sends
// its neighbours copies of its particles within reach (largest diameter + skin) of their boxes;
// every step without a build it sends them the new positions and velocities (forwardGhosts). Each
// rank evaluates every pair it lists, ghost pairs included, and uses the forces of the particles it
// owns (no reverse summation), so a pair's force is computed the same way by both its ranks.
//
// Same bits on any rank count: the arrays of every rank follow one global order, (orderKey, id)
// (ParticleSet::orderKey), so a particle's contacts are summed in the same order as on one rank;
// the rebuild vote, the Morton keys and the skin use global values; contact histories travel with
// migrating particles by particle id.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "dem/system.hpp"
#include "dem/walls/wall_overlap.hpp"

namespace gf::dem {

namespace {

struct PairKeyHash {
  std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& k) const {
    return std::hash<std::int64_t>()(k.first * 0x9E3779B97F4A7C15LL ^ k.second);
  }
};

/// What every copy of a particle carries: identity, size, order key, position and velocities (a
/// ghost: no more).
void packMotion(const ParticleSet& p, std::size_t i, parallel::Packer& out) {
  out.put(p.id[i]);
  out.put(p.type[i]);
  out.put(p.radius[i]);
  out.put(p.mass[i]);
  out.put(p.orderKey[i]);
  out.put(p.position[i]);
  out.put(p.velocity[i]);
  out.put(p.angularVelocity[i]);
}

std::size_t unpackMotion(ParticleSet& p, parallel::Unpacker& in) {
  const auto id = in.get<std::int64_t>();
  const auto type = in.get<std::int32_t>();
  const auto radius = in.get<double>();
  const auto mass = in.get<double>();
  const auto key = in.get<std::uint64_t>();
  const auto x = in.get<Vec3>();
  const auto v = in.get<Vec3>();
  const auto w = in.get<Vec3>();
  const std::size_t i = p.add(id, type, radius, 1.0, x, v, w);
  p.mass[i] = mass;  // (as sent: add() computes it from a density)
  p.orderKey[i] = key;
  return i;
}

/// Full state of one particle (migration and checkpoints): the motion, the forces of the last
/// evaluation (the next half kick uses them), the coupling's external forces and, with `columns`,
/// the set's columns.
void packParticle(const ParticleSet& p, std::size_t i, parallel::Packer& out, bool columns) {
  packMotion(p, i, out);
  out.put(p.force[i]);
  out.put(p.torque[i]);
  const bool external = p.hasExternalForces;
  out.put(static_cast<std::uint8_t>(external));
  if (external) {
    out.put(p.externalForce[i]);
    out.put(p.externalTorque[i]);
  }
  if (!columns) return;
  for (const auto& c : p.doubleColumns) out.put(c.values[i]);
  for (const auto& c : p.vec3Columns) out.put(c.values[i]);
}

std::size_t unpackParticle(ParticleSet& p, parallel::Unpacker& in, bool columns) {
  const std::size_t i = unpackMotion(p, in);
  p.force[i] = in.get<Vec3>();
  p.torque[i] = in.get<Vec3>();
  if (in.get<std::uint8_t>() != 0) {
    const Vec3 f = in.get<Vec3>(), t = in.get<Vec3>();
    if (f != Vec3{} || t != Vec3{}) {
      p.enableExternalForces();
      p.externalForce[i] = f;
      p.externalTorque[i] = t;
    }
  }
  if (columns) {
    for (auto& c : p.doubleColumns) c.values[i] = in.get<double>();
    for (auto& c : p.vec3Columns) c.values[i] = in.get<Vec3>();
  }
  return i;
}

void packGhost(const ParticleSet& p, std::size_t i, parallel::Packer& out) { packMotion(p, i, out); }

std::size_t unpackGhost(ParticleSet& p, parallel::Unpacker& in) {
  const std::size_t i = unpackMotion(p, in);
  // (a rank that owns no particle has an empty flag array, which add() does not grow)
  if (p.ghost.size() < p.size()) p.ghost.resize(p.size(), 0);
  p.ghost[i] = 1;
  return i;
}

/// The slot of `rank` in the neighbour list, or -1.
int neighbourSlot(const std::vector<int>& neighbours, int rank) {
  const auto it = std::lower_bound(neighbours.begin(), neighbours.end(), rank);
  return it != neighbours.end() && *it == rank ? static_cast<int>(it - neighbours.begin()) : -1;
}

}  // namespace

bool System::voteForRebuild(bool localReason) const {
  // The two largest displacements since the last build of the particles this rank owns, and
  // whether this rank has a reason of its own (particles came or went, lists out of date), in one
  // allgather: every rank then takes the same decision as one rank would.
  const ParticleSet& p = particles_;
  double first = 0.0, second = 0.0;
  if (positionAtBuild_.size() == p.size()) {
    const bool flags = p.ghost.size() == p.size();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 d = p.position[i] - positionAtBuild_[i];
      // (a ghost counts 0: its owner counts its displacement; a select, not a branch)
      const double m = flags && p.ghost[i] ? 0.0 : normSquared(box_.anyPeriodic ? box_.minimumImage(d) : d);
      second = std::max(second, std::min(first, m));
      first = std::max(first, m);
    }
  }
  localReason = localReason || list_.rows() != p.size() || positionAtBuild_.size() != p.size();
  parallel::Bytes mine;
  parallel::Packer out(mine);
  out.put(first);
  out.put(second);
  out.put(static_cast<std::uint8_t>(localReason));
  first = second = 0.0;
  bool anyReason = false;
  for (const parallel::Bytes& bytes : parallel::allgather(mine)) {
    parallel::Unpacker in(bytes);
    for (double m : {in.get<double>(), in.get<double>()}) {
      second = std::max(second, std::min(first, m));
      first = std::max(first, m);
    }
    anyReason = anyReason || in.get<std::uint8_t>() != 0;
  }
  return anyReason || needsRebuild(std::sqrt(first), std::sqrt(second));
}

std::vector<PairHistoryRecord> System::pairRecords(const std::vector<std::uint8_t>& ofParticle) const {
  const ParticleSet& p = particles_;
  std::vector<PairHistoryRecord> records;
  const bool rolling = list_.rollingHistory.size() == list_.entries();
  for (std::size_t r = 0; r < list_.rows(); ++r)
    for (std::uint32_t k = list_.rowStart[r]; k < list_.rowStart[r + 1]; ++k) {
      const std::uint32_t j = list_.partner[k];
      if (!ofParticle[r] && !ofParticle[j]) continue;
      const Vec3 t = list_.tangentialHistory[k];
      const Vec3 roll = rolling ? list_.rollingHistory[k] : Vec3{};
      if (t == Vec3{} && roll == Vec3{}) continue;
      if (ofParticle[r]) records.push_back({p.id[r], p.id[j], t, roll});
      else records.push_back({p.id[j], p.id[r], -1.0 * t, -1.0 * roll});
    }
  return records;
}

std::vector<WallHistoryRecord> System::wallRecords(const std::vector<std::uint8_t>& ofParticle) const {
  const ParticleSet& p = particles_;
  std::vector<WallHistoryRecord> records;
  const bool rolling = wallList_.rollingHistory.size() == wallList_.entries();
  for (std::size_t r = 0; r + 1 < wallList_.rowStart.size(); ++r) {
    if (!ofParticle[r]) continue;
    for (std::uint32_t k = wallList_.rowStart[r]; k < wallList_.rowStart[r + 1]; ++k) {
      const Vec3 t = wallList_.tangentialHistory[k], roll = rolling ? wallList_.rollingHistory[k] : Vec3{};
      if (t == Vec3{} && roll == Vec3{} && wallList_.force[k] == Vec3{}) continue;
      records.push_back({p.id[r], wallList_.primitive[k], 0, t, roll, wallList_.force[k], wallList_.point[k]});
    }
  }
  return records;
}

void System::setHistoriesFromRecords(const std::vector<PairHistoryRecord>& pairs,
                                     const std::vector<WallHistoryRecord>& walls,
                                     const std::vector<std::uint8_t>& rowsToSet) {
  const ParticleSet& p = particles_;
  if (rowsToSet.size() != p.size()) return;
  bool any = false;
  for (std::uint8_t f : rowsToSet) any |= f != 0;
  if (!any) return;
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, std::size_t, PairKeyHash> byPair;
  byPair.reserve(pairs.size());
  for (std::size_t q = 0; q < pairs.size(); ++q) byPair.emplace(std::make_pair(pairs[q].a, pairs[q].b), q);
  const bool rolling = list_.rollingHistory.size() == list_.entries();
  for (std::size_t r = 0; r < list_.rows(); ++r)
    for (std::uint32_t k = list_.rowStart[r]; k < list_.rowStart[r + 1]; ++k) {
      const std::uint32_t j = list_.partner[k];
      if (!rowsToSet[r] && !rowsToSet[j]) continue;
      Vec3 t, roll;
      if (auto it = byPair.find({p.id[r], p.id[j]}); it != byPair.end()) {
        t = pairs[it->second].tangential;
        roll = pairs[it->second].rolling;
      } else if (auto back = byPair.find({p.id[j], p.id[r]}); back != byPair.end()) {
        t = -1.0 * pairs[back->second].tangential;  // recorded in the partner's view
        roll = -1.0 * pairs[back->second].rolling;
      }
      list_.tangentialHistory[k] = t;
      if (rolling) list_.rollingHistory[k] = roll;
    }
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, std::size_t, PairKeyHash> byWall;
  for (std::size_t q = 0; q < walls.size(); ++q) byWall.emplace(std::make_pair(walls[q].id, std::int64_t{walls[q].primitive}), q);
  const bool wallRolling = wallList_.rollingHistory.size() == wallList_.entries();
  for (std::size_t r = 0; r + 1 < wallList_.rowStart.size(); ++r) {
    if (!rowsToSet[r]) continue;
    for (std::uint32_t k = wallList_.rowStart[r]; k < wallList_.rowStart[r + 1]; ++k) {
      WallHistoryRecord w;
      if (auto it = byWall.find({p.id[r], std::int64_t{wallList_.primitive[k]}}); it != byWall.end()) w = walls[it->second];
      wallList_.tangentialHistory[k] = w.tangential;
      if (wallRolling) wallList_.rollingHistory[k] = w.rolling;
      wallList_.force[k] = w.force;
      wallList_.point[k] = w.point;
    }
  }
}

void System::migrateAndExchangeGhosts(const std::vector<std::uint32_t>& order, bool reorder, double mortonCell,
                                      double ghostReach, std::vector<std::int64_t>& previous, std::size_t listedRows) {
  ParticleSet& p = particles_;
  // New boxes (a rebalancing, system_rebalance.cpp): the particles then go to any rank.
  const bool anywhere = rebalanceIfDue(order, ghostReach);
  decomposition_.setReach(ghostReach);
  const std::vector<int>& neighbours = decomposition_.neighbourRanks();
  const int me = decomposition_.rank();
  // 1. Particles that left this rank's box go to the rank whose box holds them, with their contact
  //    histories; ghosts are dropped (sent again below).
  std::vector<std::uint32_t> stay;
  std::vector<std::vector<std::uint32_t>> leave(anywhere ? static_cast<std::size_t>(decomposition_.ranks())
                                                         : neighbours.size());
  std::vector<std::uint8_t> leaving(p.size(), 0);
  std::unordered_map<std::int64_t, std::uint32_t> formerIndex;  // former ghosts and leaving particles, by id
  for (std::uint32_t i : order) {
    if (p.isGhost(i)) {
      if (i < listedRows) formerIndex.emplace(p.id[i], i);
      continue;
    }
    const int owner = decomposition_.ownerOf(p.position[i]);
    if (owner == me) {
      stay.push_back(i);
      continue;
    }
    const int slot = anywhere ? owner : neighbourSlot(neighbours, owner);
    if (slot < 0)
      throw DivergenceError(steps_, time_, "particle moved beyond the neighbouring ranks' boxes within one list build",
                            fmt::format("particle id {} (rank {} to rank {})", p.id[i], me, owner), p.position[i],
                            "use fewer ranks along that axis or a smaller time step");
    leave[static_cast<std::size_t>(slot)].push_back(i);
    leaving[i] = 1;
    if (i < listedRows) formerIndex.emplace(p.id[i], i);
  }
  std::vector<PairHistoryRecord> pairs = pairRecords(leaving);
  std::vector<WallHistoryRecord> walls = wallRecords(leaving);
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.a < b.a; });
  std::sort(walls.begin(), walls.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  std::vector<parallel::Bytes> send(leave.size());
  for (std::size_t n = 0; n < leave.size(); ++n) {
    parallel::Packer out(send[n]);
    for (std::uint32_t i : leave[n]) {
      packParticle(p, i, out, true);
      const std::int64_t id = p.id[i];
      auto pr = std::equal_range(pairs.begin(), pairs.end(), PairHistoryRecord{id, 0, {}, {}},
                                 [](const auto& a, const auto& b) { return a.a < b.a; });
      out.put(static_cast<std::uint32_t>(pr.second - pr.first));
      for (auto it = pr.first; it != pr.second; ++it) out.put(*it);
      WallHistoryRecord key;
      key.id = id;
      auto wr = std::equal_range(walls.begin(), walls.end(), key, [](const auto& a, const auto& b) { return a.id < b.id; });
      out.put(static_cast<std::uint32_t>(wr.second - wr.first));
      for (auto it = wr.first; it != wr.second; ++it) out.put(*it);
    }
  }
  const std::vector<parallel::Bytes> received =
      anywhere ? parallel::exchangeWithAny(send) : parallel::exchange(neighbours, send);

  // 2. The staying particles (in their order), then the arrivals.
  p.gather(stay);
  p.ghost.assign(p.size(), 0);
  std::vector<std::int64_t> origin(stay.begin(), stay.end());  // former index per current index (-1: look up by id)
  arrivedPairs_.clear();
  arrivedWalls_.clear();
  for (const parallel::Bytes& bytes : received) {
    parallel::Unpacker in(bytes);
    while (!in.done()) {
      unpackParticle(p, in, true);
      origin.push_back(-1);
      const auto pairCount = in.get<std::uint32_t>();
      for (std::uint32_t q = 0; q < pairCount; ++q) arrivedPairs_.push_back(in.get<PairHistoryRecord>());
      const auto wallCount = in.get<std::uint32_t>();
      for (std::uint32_t q = 0; q < wallCount; ++q) arrivedWalls_.push_back(in.get<WallHistoryRecord>());
    }
  }
  const std::size_t owned = p.size();
  std::vector<std::uint8_t> arrived(owned, 0);
  for (std::size_t i = stay.size(); i < owned; ++i) arrived[i] = 1;

  // 3. Order keys (a reordering build), ghosts, and the common order.
  if (reorder && owned > 0) {
    std::vector<std::uint32_t> all(owned);
    for (std::size_t i = 0; i < owned; ++i) all[i] = static_cast<std::uint32_t>(i);
    assignMortonKeys(all, mortonCell);
  }
  const std::vector<std::uint32_t> permutation = exchangeGhosts(ghostReach);
  previous.assign(p.size(), -1);
  arrived_.assign(p.size(), 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const std::uint32_t before = permutation[k];
    std::int64_t former = before < owned ? origin[before] : -1;
    if (before < owned) arrived_[k] = arrived[before];
    if (former < 0) {
      const auto it = formerIndex.find(p.id[k]);
      if (it != formerIndex.end()) former = it->second;
    }
    previous[k] = former >= 0 && static_cast<std::size_t>(former) < listedRows ? former : -1;
  }
}

std::vector<std::uint32_t> System::exchangeGhosts(double reach) {
  ParticleSet& p = particles_;
  decomposition_.setReach(reach);  // (explicit boxes: the neighbours within reach)
  const std::vector<int>& neighbours = decomposition_.neighbourRanks();
  ghostReach_ = reach;
  const std::size_t owned = p.size();
  p.ghost.assign(owned, 0);
  ghostSend_.assign(neighbours.size(), {});
  ghostReceive_.assign(neighbours.size(), {});
  std::vector<parallel::Bytes> send(neighbours.size());
  for (std::size_t n = 0; n < neighbours.size(); ++n) {
    parallel::Packer out(send[n]);
    for (std::size_t i = 0; i < owned; ++i) {
      const Vec3 d = decomposition_.distanceToBox(p.position[i], neighbours[n]);
      if (d.x < reach && d.y < reach && d.z < reach) {
        packGhost(p, i, out);
        ghostSend_[n].push_back(static_cast<std::uint32_t>(i));
      }
    }
  }
  const std::vector<parallel::Bytes> received = parallel::exchange(neighbours, send);
  for (std::size_t n = 0; n < neighbours.size(); ++n) {
    parallel::Unpacker in(received[n]);
    while (!in.done()) ghostReceive_[n].push_back(static_cast<std::uint32_t>(unpackGhost(p, in)));
  }
  // One order for owned particles and ghosts together: (orderKey, id), the same on every rank.
  std::vector<std::uint32_t> permutation(p.size());
  for (std::size_t i = 0; i < permutation.size(); ++i) permutation[i] = static_cast<std::uint32_t>(i);
  sortByKeyThenId(permutation, p);
  p.gather(permutation);
  std::vector<std::uint32_t> newIndex(permutation.size());
  for (std::size_t k = 0; k < permutation.size(); ++k) newIndex[permutation[k]] = static_cast<std::uint32_t>(k);
  for (auto* lists : {&ghostSend_, &ghostReceive_})
    for (auto& list : *lists)
      for (std::uint32_t& i : list) i = newIndex[i];
  return permutation;
}

void System::forwardGhosts() {
  ParticleSet& p = particles_;
  std::vector<parallel::Bytes> send(ghostSend_.size());
  constexpr std::size_t kRecord = 3 * sizeof(Vec3);  // position, velocity, angular velocity
  for (std::size_t n = 0; n < ghostSend_.size(); ++n) {
    send[n].resize(ghostSend_[n].size() * kRecord);
    char* out = send[n].data();
    for (std::uint32_t i : ghostSend_[n]) {
      std::memcpy(out, &p.position[i], sizeof(Vec3));
      std::memcpy(out + sizeof(Vec3), &p.velocity[i], sizeof(Vec3));
      std::memcpy(out + 2 * sizeof(Vec3), &p.angularVelocity[i], sizeof(Vec3));
      out += kRecord;
    }
  }
  // (each side knows the sizes from the last list build: one message round)
  std::vector<std::size_t> receiveBytes(ghostReceive_.size());
  for (std::size_t n = 0; n < ghostReceive_.size(); ++n) receiveBytes[n] = ghostReceive_[n].size() * kRecord;
  const std::vector<parallel::Bytes> received =
      parallel::exchangeKnownSizes(decomposition_.neighbourRanks(), send, receiveBytes);
  for (std::size_t n = 0; n < received.size(); ++n) {
    const char* in = received[n].data();
    for (std::uint32_t i : ghostReceive_[n]) {
      std::memcpy(&p.position[i], in, sizeof(Vec3));
      std::memcpy(&p.velocity[i], in + sizeof(Vec3), sizeof(Vec3));
      std::memcpy(&p.angularVelocity[i], in + 2 * sizeof(Vec3), sizeof(Vec3));
      in += kRecord;
    }
  }
}

long long System::globalParticleCount() const {
  const auto owned = static_cast<long long>(particles_.ownedCount());
  return distributed_ ? parallel::sumOverRanks(owned) : owned;
}

ParticleSet System::gatherParticles() const {
  const ParticleSet& p = particles_;
  ParticleSet all;
  if (!distributed_) {
    all = p;
    return all;
  }
  parallel::Bytes mine;
  parallel::Packer out(mine);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!p.isGhost(i)) packParticle(p, i, out, false);
  const std::vector<parallel::Bytes> parts = parallel::gatherToRoot(mine);
  for (const parallel::Bytes& bytes : parts) {
    parallel::Unpacker in(bytes);
    while (!in.done()) unpackParticle(all, in, false);
  }
  std::vector<std::uint32_t> byId(all.size());
  for (std::size_t i = 0; i < byId.size(); ++i) byId[i] = static_cast<std::uint32_t>(i);
  std::sort(byId.begin(), byId.end(), [&](std::uint32_t a, std::uint32_t b) { return all.id[a] < all.id[b]; });
  all.gather(byId);
  return all;
}

// ------------------------------------------------------------------ checkpoint

void System::save(BinaryWriter& out) const {
  const ParticleSet& p = particles_;
  out.put(time_);
  out.put(steps_);
  out.put(nextId_);
  out.put(rebuilds_);
  out.put(timeAtBuild_);
  out.put(skin_);
  // The owned particles of every rank in the common order (orderKey, id), each with its position
  // at the last build; contact histories by particle ids (each pair once: by its row's owner).
  std::vector<std::uint8_t> owned(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) owned[i] = p.isGhost(i) ? 0 : 1;
  std::vector<PairHistoryRecord> pairs;
  std::vector<WallHistoryRecord> walls = wallRecords(owned);
  {
    const ParticleSet& q = p;
    const bool rolling = list_.rollingHistory.size() == list_.entries();
    for (std::size_t r = 0; r < list_.rows(); ++r) {
      if (!owned[r]) continue;
      for (std::uint32_t k = list_.rowStart[r]; k < list_.rowStart[r + 1]; ++k) {
        const Vec3 t = list_.tangentialHistory[k], roll = rolling ? list_.rollingHistory[k] : Vec3{};
        if (t != Vec3{} || roll != Vec3{}) pairs.push_back({q.id[r], q.id[list_.partner[k]], t, roll});
      }
    }
  }
  ParticleSet all;
  std::vector<Vec3> atBuild;
  if (!distributed_) {
    p.save(out);
    out.putVector(positionAtBuild_);
  } else {
    parallel::Bytes mine;
    parallel::Packer pack(mine);
    for (std::size_t i = 0; i < p.size(); ++i)
      if (owned[i]) {
        packParticle(p, i, pack, false);
        pack.put(positionAtBuild_[i]);
      }
    parallel::Bytes records;
    parallel::Packer packRecords(records);
    packRecords.put(static_cast<std::uint64_t>(pairs.size()));
    for (const auto& r : pairs) packRecords.put(r);
    packRecords.put(static_cast<std::uint64_t>(walls.size()));
    for (const auto& r : walls) packRecords.put(r);
    const std::vector<parallel::Bytes> parts = parallel::gatherToRoot(mine);
    const std::vector<parallel::Bytes> recordParts = parallel::gatherToRoot(records);
    for (const parallel::Bytes& bytes : parts) {
      parallel::Unpacker in(bytes);
      while (!in.done()) {
        unpackParticle(all, in, false);
        atBuild.push_back(in.get<Vec3>());
      }
    }
    pairs.clear();
    walls.clear();
    for (const parallel::Bytes& bytes : recordParts) {
      parallel::Unpacker in(bytes);
      const auto np = in.get<std::uint64_t>();
      for (std::uint64_t q = 0; q < np; ++q) pairs.push_back(in.get<PairHistoryRecord>());
      const auto nw = in.get<std::uint64_t>();
      for (std::uint64_t q = 0; q < nw; ++q) walls.push_back(in.get<WallHistoryRecord>());
    }
    std::vector<std::uint32_t> order(all.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
    sortByKeyThenId(order, all);
    all.gather(order);
    std::vector<Vec3> sortedAtBuild(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) sortedAtBuild[k] = atBuild[order[k]];
    all.save(out);
    out.putVector(sortedAtBuild);
  }
  // Records sorted by ids: the same file for any rank count.
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.a != b.a ? a.a < b.a : a.b < b.b; });
  std::sort(walls.begin(), walls.end(),
            [](const auto& a, const auto& b) { return a.id != b.id ? a.id < b.id : a.primitive < b.primitive; });
  out.putVector(pairs);
  out.putVector(walls);
  for (const auto& ins : inserters_) ins->save(out);
  for (const Outlet& o : outlets_) {
    out.put(distributed_ ? parallel::sumOverRanks(o.removedMass) : o.removedMass);
    out.put(distributed_ ? parallel::sumOverRanks(o.removedCount) : o.removedCount);
  }
}

void System::load(BinaryReader& in) {
  ParticleSet& p = particles_;
  time_ = in.get<double>();
  steps_ = in.get<long long>();
  nextId_ = in.get<std::int64_t>();
  rebuilds_ = in.get<long long>();
  timeAtBuild_ = in.get<double>();
  skin_ = in.get<double>();
  p.load(in);
  std::vector<Vec3> atBuild = in.getVector<Vec3>();
  const std::vector<PairHistoryRecord> pairs = in.getVector<PairHistoryRecord>();
  const std::vector<WallHistoryRecord> walls = in.getVector<WallHistoryRecord>();
  if (atBuild.size() != p.size()) throw CheckpointError("checkpoint is corrupt: DEM positions do not match the particles");
  for (auto& ins : inserters_) ins->load(in);
  for (Outlet& o : outlets_) {
    o.removedMass = in.get<double>();
    o.removedCount = in.get<long long>();
    // (the run's totals: kept by rank 0, summed over ranks by the monitors)
    if (distributed_ && decomposition_.rank() != 0) o.removedMass = 0.0, o.removedCount = 0;
  }
  // The lists as the run built them: at the positions (and wall positions) of the last build, the
  // particles each rank owned then, and the ghosts of that moment.
  std::vector<Vec3> current = p.position;
  p.position = atBuild;
  std::vector<std::uint32_t> permutation(p.size());
  for (std::size_t i = 0; i < permutation.size(); ++i) permutation[i] = static_cast<std::uint32_t>(i);
  if (distributed_) {
    std::vector<std::uint32_t> mine;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (decomposition_.ownerOf(atBuild[i]) == decomposition_.rank()) mine.push_back(static_cast<std::uint32_t>(i));
    p.gather(mine);
    double maxDiameter = 0.0;
    for (double r : p.radius) maxDiameter = std::max(maxDiameter, 2.0 * r);
    maxDiameter = parallel::maxOverRanks(maxDiameter);
    const std::vector<std::uint32_t> sorted = exchangeGhosts(maxDiameter + skin_);
    permutation.assign(sorted.size(), 0);
    for (std::size_t k = 0; k < sorted.size(); ++k) permutation[k] = sorted[k] < mine.size() ? mine[sorted[k]] : ~0u;
  }
  const double now = time_;
  time_ = timeAtBuild_;
  updateWalls();
  const std::vector<std::int64_t> none(p.size(), -1);
  const bool rollingHistory = table_.rollingLaw() == RollingLaw::Epsd;
  list_.build(p, box_, domain_.min, domain_.max, skin_, none, rollingHistory);
  wallList_.build(p, primitives_, skin_, none, rollingHistory);
  setHistoriesFromRecords(pairs, walls, std::vector<std::uint8_t>(p.size(), 1));
  time_ = now;
  updateWalls();
  positionAtBuild_ = p.position;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (permutation[k] != ~0u) p.position[k] = current[permutation[k]];
  updateInverseInertia();
  if (distributed_) forwardGhosts();
}

}  // namespace gf::dem
