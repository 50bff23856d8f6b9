#include "dem/system.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "core/parallel.hpp"

namespace gf::dem {

namespace {

std::vector<Material> readMaterials(Params& root) {
  std::vector<Material> out;
  for (Params& m : root.list({"materials", "-", "particle materials (index = position in the list)"})) {
    Material mat;
    mat.name = m.text({"name", "-", "material name"});
    mat.density = m.real({"density", "kg/m^3", "solid density", Range::positive()});
    mat.youngsModulus = m.real({"youngs_modulus", "Pa", "Young's modulus E", Range::positive()}, 1e7);
    mat.poissonRatio = m.real({"poisson_ratio", "-", "Poisson ratio", Range{-1.0, 0.5, false, false}}, 0.3);
    mat.restitution = m.real({"restitution", "-", "coefficient of restitution e", Range{0.0, 1.0, false, true}}, 0.5);
    mat.friction = m.real({"friction", "-", "sliding friction coefficient", Range::nonNegative()}, 0.5);
    out.push_back(mat);
  }
  if (out.empty() && !root.documenting())
    root.fail("materials", "no material", "a list with at least one material (name, density, ...)");
  return out;
}

}  // namespace

System::System(Params& root, const Domain& domain, const Vec3& gravity) : domain_(domain), gravity_(gravity) {
  materials_ = readMaterials(root);

  for (Params& w : root.list({"walls", "-", "walls bounding the particles"})) {
    w.choice({"type", "-", "wall type"}, {"plane"});
    PlaneWall wall;
    wall.point = w.vec3({"point", "m", "a point on the plane"});
    const Vec3 n = w.vec3({"normal", "-", "normal pointing into the particle region"});
    if (!w.documenting() && norm(n) == 0.0) w.fail("normal", "[0, 0, 0]", "a non-zero vector");
    wall.normal = normalized(n);
    walls_.push_back(wall);
  }

  std::int64_t nextId = 0;
  for (Params& ins : root.list({"insertion", "-", "initial particle insertion"})) {
    ins.choice({"type", "-", "insertion method"}, {"lattice"});
    const Vec3 origin = ins.vec3({"origin", "m", "centre of the first particle"});
    const double spacing = ins.real({"spacing", "m", "lattice spacing", Range::positive()});
    const double count[3] = {
        static_cast<double>(ins.integer({"nx", "-", "particles along x", Range::atLeast(1)}, 1)),
        static_cast<double>(ins.integer({"ny", "-", "particles along y", Range::atLeast(1)}, 1)),
        static_cast<double>(ins.integer({"nz", "-", "particles along z", Range::atLeast(1)}, 1))};
    const double diameter = ins.real({"diameter", "m", "particle diameter", Range::positive()});
    const Vec3 velocity = ins.vec3({"velocity", "m/s", "initial velocity"}, {});
    const std::string materialName = ins.text({"material", "-", "material name"}, materials_.empty() ? "" : materials_[0].name);
    if (ins.documenting()) continue;
    int materialIndex = -1;
    for (std::size_t m = 0; m < materials_.size(); ++m)
      if (materials_[m].name == materialName) materialIndex = static_cast<int>(m);
    if (materialIndex < 0) ins.fail("material", "'" + materialName + "'", "the name of a material in 'materials'");
    for (int k = 0; k < count[2]; ++k)
      for (int j = 0; j < count[1]; ++j)
        for (int i = 0; i < count[0]; ++i) {
          const Vec3 x = origin + Vec3{i * spacing, j * spacing, k * spacing};
          if (!domain_.contains(x))
            ins.fail("origin", fmt::format("a particle at ({:g}, {:g}, {:g}) outside the domain", x.x, x.y, x.z),
                     "all lattice points inside 'domain'");
          particles_.add(nextId++, materialIndex, 0.5 * diameter, materials_[materialIndex].density, x, velocity);
        }
  }
  computeForces();
}

double System::rayleighTime() const {
  // Rayleigh time t_R = pi r sqrt(rho/G) / (0.1631 nu + 0.8766) (e.g. Li et al. 2005).
  double tMin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Material& m = materials_[particles_.type[i]];
    const double shearModulus = m.youngsModulus / (2.0 * (1.0 + m.poissonRatio));
    const double t = std::numbers::pi * particles_.radius[i] * std::sqrt(m.density / shearModulus) /
                     (0.1631 * m.poissonRatio + 0.8766);
    tMin = std::min(tMin, t);
  }
  return tMin;
}

namespace {
// Hertz normal force with viscoelastic damping (Tsuji et al. 1992 form used by LIGGGHTS
// 'hertz'): F = 4/3 E* sqrt(R* d) d - 2 sqrt(5/6) beta sqrt(S_n m*) v_n, S_n = 2 E* sqrt(R* d),
// beta = ln e / sqrt(ln^2 e + pi^2).
double hertzNormalForce(double overlap, double normalVelocity, double effectiveE, double effectiveR,
                        double effectiveMass, double restitution) {
  const double sqrtRd = std::sqrt(effectiveR * overlap);
  const double stiffness = 2.0 * effectiveE * sqrtRd;
  const double logE = std::log(restitution);
  const double beta = logE / std::sqrt(logE * logE + std::numbers::pi * std::numbers::pi);
  const double elastic = 4.0 / 3.0 * effectiveE * sqrtRd * overlap;
  const double damping = 2.0 * std::sqrt(5.0 / 6.0) * beta * std::sqrt(stiffness * effectiveMass) * normalVelocity;
  return elastic + damping;
}
}  // namespace

void System::computeForces() {
  ParticleSet& p = particles_;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  parallelFor(n, [&](std::int64_t i) {
    p.force[i] = p.mass[i] * gravity_ + p.externalForce[i];
    p.torque[i] = p.externalTorque[i];
  });
  ScopedPhase timer(timers_, Phase::Contacts);
  parallelFor(n, [&](std::int64_t i) {
    const Material& mi = materials_[p.type[i]];
    const double Ei = mi.youngsModulus / (1.0 - mi.poissonRatio * mi.poissonRatio);
    for (std::int64_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const Vec3 d = p.position[i] - p.position[j];
      const double dist2 = normSquared(d);
      const double rsum = p.radius[i] + p.radius[j];
      if (dist2 >= rsum * rsum) continue;
      const double dist = std::sqrt(dist2);
      const Vec3 normal = d / dist;
      const Material& mj = materials_[p.type[j]];
      const double Ej = mj.youngsModulus / (1.0 - mj.poissonRatio * mj.poissonRatio);
      const double effectiveE = 1.0 / (1.0 / Ei + 1.0 / Ej);
      const double effectiveR = p.radius[i] * p.radius[j] / rsum;
      const double effectiveMass = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
      const double vn = dot(p.velocity[i] - p.velocity[j], normal);
      const double e = 0.5 * (mi.restitution + mj.restitution);
      const double f = hertzNormalForce(rsum - dist, vn, effectiveE, effectiveR, effectiveMass, e);
      p.force[i] += f * normal;
    }
    for (const PlaneWall& w : walls_) {
      const double gap = dot(p.position[i] - w.point, w.normal);
      const double overlap = p.radius[i] - gap;
      if (overlap <= 0.0) continue;
      const double vn = dot(p.velocity[i], w.normal);
      const double f = hertzNormalForce(overlap, vn, Ei, p.radius[i], p.mass[i], mi.restitution);
      p.force[i] += f * w.normal;
    }
  });
}

void System::step(double dt) {
  ParticleSet& p = particles_;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  {
    // Velocity Verlet: half kick with old forces, drift.
    ScopedPhase timer(timers_, Phase::Integration);
    parallelFor(n, [&](std::int64_t i) {
      p.velocity[i] += 0.5 * dt / p.mass[i] * p.force[i];
      p.position[i] += dt * p.velocity[i];
    });
  }
  computeForces();
  ScopedPhase timer(timers_, Phase::Integration);
  parallelFor(n, [&](std::int64_t i) { p.velocity[i] += 0.5 * dt / p.mass[i] * p.force[i]; });
}

void System::checkHealth(long long step, double time) const {
  const ParticleSet& p = particles_;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!isFinite(p.position[i]) || !isFinite(p.velocity[i]))
      throw DivergenceError(step, time, "particle position/velocity is NaN or Inf",
                            fmt::format("particle id {}", p.id[i]), p.position[i], "reduce the time step");
    Vec3 x = p.position[i];
    bool inside = true;
    for (int a = 0; a < 3; ++a)
      if (!domain_.periodic[a] && (x[a] < domain_.min[a] || x[a] > domain_.max[a])) inside = false;
    if (!inside)
      throw DivergenceError(step, time, "particle left the domain", fmt::format("particle id {}", p.id[i]), x,
                            "no outlet removes it; check walls and time step");
  }
}

void System::save(BinaryWriter& out) const { particles_.save(out); }
void System::load(BinaryReader& in) { particles_.load(in); }

}  // namespace gf::dem
