#include "dem/particles.hpp"

#include <numbers>

namespace gf::dem {

std::size_t ParticleSet::add(std::int64_t newId, std::int32_t materialType, double r, double density, const Vec3& x,
                             const Vec3& v, const Vec3& omega) {
  id.push_back(newId);
  type.push_back(materialType);
  radius.push_back(r);
  mass.push_back(density * 4.0 / 3.0 * std::numbers::pi * r * r * r);
  position.push_back(x);
  velocity.push_back(v);
  angularVelocity.push_back(omega);
  force.push_back({});
  torque.push_back({});
  externalForce.push_back({});
  externalTorque.push_back({});
  return id.size() - 1;
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
}

void ParticleSet::load(BinaryReader& in) {
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
  const std::size_t n = id.size();
  if (type.size() != n || radius.size() != n || mass.size() != n || position.size() != n || velocity.size() != n ||
      angularVelocity.size() != n || force.size() != n || torque.size() != n || externalForce.size() != n ||
      externalTorque.size() != n)
    throw CheckpointError("checkpoint is corrupt: particle arrays have different lengths");
}

}  // namespace gf::dem
