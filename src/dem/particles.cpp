#include "dem/particles.hpp"

#include <algorithm>
#include <atomic>
#include <numbers>

#include "core/parallel.hpp"

namespace gf::dem {

std::uint64_t ParticleSet::nextLayoutStamp() {
  static std::atomic<std::uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

std::size_t ParticleSet::add(std::int64_t newId, std::int32_t materialType, double r, double density, const Vec3& x,
                             const Vec3& v, const Vec3& omega) {
  touchLayout();
  id.push_back(newId);
  type.push_back(materialType);
  radius.push_back(r);
  mass.push_back(density * 4.0 / 3.0 * std::numbers::pi * r * r * r);
  position.push_back(x);
  velocity.push_back(v);
  angularVelocity.push_back(omega);
  force.push_back({});
  torque.push_back({});
  orderKey.push_back(kNewParticleKey);
  if (!ghost.empty()) ghost.push_back(0);
  if (hasExternalForces) {
    externalForce.push_back({});
    externalTorque.push_back({});
  }
  for (auto& c : doubleColumns) c.values.push_back(c.fill);
  for (auto& c : vec3Columns) c.values.push_back(c.fill);
  return id.size() - 1;
}

namespace {
template <class T>
std::size_t findColumn(const std::vector<ParticleSet::Column<T>>& columns, const std::string& name) {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].name == name) return c;
  return ParticleSet::kNoColumn;
}

template <class T>
std::size_t addColumnTo(std::vector<ParticleSet::Column<T>>& columns, const std::string& name, const T& fill,
                        std::size_t n) {
  const std::size_t found = findColumn(columns, name);
  if (found != ParticleSet::kNoColumn) return found;
  columns.push_back({name, fill, std::vector<T>(n, fill)});
  return columns.size() - 1;
}
}  // namespace

std::size_t ParticleSet::addColumn(const std::string& name, double fill) {
  return addColumnTo(doubleColumns, name, fill, size());
}

std::size_t ParticleSet::addColumn(const std::string& name, const Vec3& fill) {
  return addColumnTo(vec3Columns, name, fill, size());
}

std::size_t ParticleSet::findDoubleColumn(const std::string& name) const { return findColumn(doubleColumns, name); }

std::size_t ParticleSet::findVec3Column(const std::string& name) const { return findColumn(vec3Columns, name); }

std::size_t ParticleSet::ownedCount() const {
  if (ghost.empty()) return size();
  std::size_t n = 0;
  for (std::uint8_t g : ghost) n += g == 0 ? 1 : 0;
  return n;
}

void ParticleSet::enableExternalForces() {
  if (hasExternalForces) return;
  externalForce.assign(size(), Vec3{});
  externalTorque.assign(size(), Vec3{});
  hasExternalForces = true;
  hasExternalTorques = true;
}

void ParticleSet::clearExternalTorques() {
  if (hasExternalTorques) std::fill(externalTorque.begin(), externalTorque.end(), Vec3{});
  hasExternalTorques = false;
}

void ParticleSet::reserve(std::size_t n) {
  id.reserve(n);
  type.reserve(n);
  radius.reserve(n);
  mass.reserve(n);
  position.reserve(n);
  velocity.reserve(n);
  angularVelocity.reserve(n);
  force.reserve(n);
  torque.reserve(n);
  orderKey.reserve(n);
  if (hasExternalForces) {
    externalForce.reserve(n);
    externalTorque.reserve(n);
  }
  for (auto& c : doubleColumns) c.values.reserve(n);
  for (auto& c : vec3Columns) c.values.reserve(n);
}

namespace {
template <class T>
void gatherArray(std::vector<T>& a, const std::vector<std::uint32_t>& order) {
  std::vector<T> out(order.size());
  parallelFor(static_cast<std::int64_t>(order.size()), [&](std::int64_t k) { out[k] = a[order[k]]; });
  a.swap(out);
}
}  // namespace

void ParticleSet::gather(const std::vector<std::uint32_t>& order) {
  touchLayout();
  gatherArray(id, order);
  gatherArray(type, order);
  gatherArray(radius, order);
  gatherArray(mass, order);
  gatherArray(position, order);
  gatherArray(velocity, order);
  gatherArray(angularVelocity, order);
  gatherArray(force, order);
  gatherArray(torque, order);
  gatherArray(orderKey, order);
  if (!ghost.empty()) gatherArray(ghost, order);
  if (hasExternalForces) {
    gatherArray(externalForce, order);
    gatherArray(externalTorque, order);
  }
  for (auto& c : doubleColumns) gatherArray(c.values, order);
  for (auto& c : vec3Columns) gatherArray(c.values, order);
}

void ParticleSet::save(BinaryWriter& out) const {
  out.putVector(id);
  out.putVector(type);
  out.putVector(radius);
  out.putVector(mass);
  out.putVector(position);
  out.putVector(velocity);
  out.putVector(angularVelocity);
  out.putVector(force);
  out.putVector(torque);
  out.putVector(externalForce);
  out.putVector(externalTorque);
  out.putVector(orderKey);
}

void ParticleSet::load(BinaryReader& in) {
  touchLayout();
  id = in.getVector<std::int64_t>();
  type = in.getVector<std::int32_t>();
  radius = in.getVector<double>();
  mass = in.getVector<double>();
  position = in.getVector<Vec3>();
  velocity = in.getVector<Vec3>();
  angularVelocity = in.getVector<Vec3>();
  force = in.getVector<Vec3>();
  torque = in.getVector<Vec3>();
  externalForce = in.getVector<Vec3>();
  externalTorque = in.getVector<Vec3>();
  orderKey = in.getVector<std::uint64_t>();
  ghost.clear();
  const std::size_t n = id.size();
  if (type.size() != n || radius.size() != n || mass.size() != n || position.size() != n || velocity.size() != n ||
      angularVelocity.size() != n || force.size() != n || torque.size() != n || orderKey.size() != n ||
      externalForce.size() != externalTorque.size() || (!externalForce.empty() && externalForce.size() != n))
    throw CheckpointError("checkpoint is corrupt: particle arrays have different lengths");
  // External forces that are all zero (a DEM-only run, or a checkpoint written before they were
  // sized on demand) are dropped: the force loop gives the same result without them.
  bool anyTorque = false;
  for (std::size_t i = 0; i < externalTorque.size() && !anyTorque; ++i) anyTorque = normSquared(externalTorque[i]) != 0.0;
  bool anyExternal = anyTorque;
  for (std::size_t i = 0; i < externalForce.size() && !anyExternal; ++i) anyExternal = normSquared(externalForce[i]) != 0.0;
  hasExternalForces = anyExternal;
  hasExternalTorques = anyTorque;
  if (!anyExternal) {
    externalForce = {};
    externalTorque = {};
  }
  // (registered columns stay, every particle at its fill value: their owners restore their own)
  for (auto& c : doubleColumns) c.values.assign(n, c.fill);
  for (auto& c : vec3Columns) c.values.assign(n, c.fill);
}

}  // namespace gf::dem
