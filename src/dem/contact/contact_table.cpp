#include "dem/contact/contact_table.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/params.hpp"

namespace gf::dem {

double effectiveYoungs(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poissonRatio * a.poissonRatio) / a.youngsModulus +
                (1.0 - b.poissonRatio * b.poissonRatio) / b.youngsModulus);
}
double effectiveShear(const Material& a, const Material& b) {
  return 1.0 / (2.0 * (2.0 - a.poissonRatio) * (1.0 + a.poissonRatio) / a.youngsModulus +
                2.0 * (2.0 - b.poissonRatio) * (1.0 + b.poissonRatio) / b.youngsModulus);
}

namespace {

std::vector<Material> readMaterials(Params& root) {
  std::vector<Material> out;
  for (Params& m : root.list({"materials", "-", "particle and wall materials (index = position in the list)"})) {
    Material mat;
    mat.name = m.text({"name", "-", "material name (referenced by insertion and walls)"});
    mat.density = m.real({"density", "kg/m^3", "solid density", Range::positive()}, 2500.0);
    mat.youngsModulus = m.real({"youngs_modulus", "Pa", "Young's modulus E", Range::positive()}, 1e7);
    mat.poissonRatio = m.real({"poisson_ratio", "-", "Poisson ratio nu", Range{-1.0, 0.5, false, false}}, 0.3);
    // Optional per-material shortcuts for the pair parameters (see contact.pairs).
    auto optional = [&](const Key& k, Range r) {
      return m.has(k.name) || m.documenting() ? m.real({k.name, k.unit, k.help, r}, 0.0)
                                              : std::numeric_limits<double>::quiet_NaN();
    };
    mat.restitution = optional({"restitution", "-", "optional: restitution e of this material (pair: mean)"},
                               Range{0.0, 1.0, false, true});
    mat.friction = optional({"friction", "-", "optional: sliding friction mu of this material (pair: mean)"},
                            Range::nonNegative());
    mat.rollingFriction = optional({"rolling_friction", "-", "optional: rolling friction mu_r (pair: mean)"},
                                   Range::nonNegative());
    mat.cohesionEnergyDensity = optional(
        {"cohesion_energy_density", "J/m^3", "optional: cohesion energy density (pair: mean)"}, Range::nonNegative());
    out.push_back(mat);
  }
  if (out.empty() && !root.documenting())
    root.fail("materials", "no material", "a list with at least one material (name, density, ...)");
  return out;
}

PairProperties readPairProperties(Params& p, const PairProperties& defaults) {
  PairProperties q;
  q.restitution = p.real({"restitution", "-", "coefficient of normal restitution e", Range{0.0, 1.0, false, true}},
                         defaults.restitution);
  q.friction = p.real({"friction", "-", "sliding friction coefficient mu", Range::nonNegative()}, defaults.friction);
  q.rollingFriction = p.real({"rolling_friction", "-", "rolling friction coefficient mu_r", Range::nonNegative()},
                             defaults.rollingFriction);
  q.cohesionEnergyDensity =
      p.real({"cohesion_energy_density", "J/m^3", "cohesion energy density k_c (simplified_jkr)",
              Range::nonNegative()},
             defaults.cohesionEnergyDensity);
  return q;
}

/// Pair values from the per-material shortcuts: mean of the values given, else the default.
PairProperties materialPair(const Material& a, const Material& b, const PairProperties& defaults) {
  auto combine = [](double x, double y, double fallback) {
    if (!std::isnan(x) && !std::isnan(y)) return 0.5 * (x + y);
    if (!std::isnan(x)) return x;
    if (!std::isnan(y)) return y;
    return fallback;
  };
  PairProperties p;
  p.restitution = combine(a.restitution, b.restitution, defaults.restitution);
  p.friction = combine(a.friction, b.friction, defaults.friction);
  p.rollingFriction = combine(a.rollingFriction, b.rollingFriction, defaults.rollingFriction);
  p.cohesionEnergyDensity = combine(a.cohesionEnergyDensity, b.cohesionEnergyDensity, defaults.cohesionEnergyDensity);
  return p;
}

}  // namespace

void ContactTable::addRigidMaterial() {
  if (materialIndex(kRigidMaterial) >= 0) return;  // the case defines its own
  Material rigid;
  rigid.name = kRigidMaterial;
  rigid.isBuiltInRigid = true;
  rigid.youngsModulus = std::numeric_limits<double>::infinity();  // E* = E_p / (1 - nu_p^2)
  materials_.push_back(rigid);
}

int ContactTable::materialIndex(const std::string& name) const {
  for (std::size_t m = 0; m < materials_.size(); ++m)
    if (materials_[m].name == name) return static_cast<int>(m);
  return -1;
}

int ContactTable::readMaterial(Params& p, const Key& k, const std::string& defaultName) const {
  const std::string fallback = defaultName.empty() && !materials_.empty() ? materials_.front().name : defaultName;
  const std::string name = p.text(k, fallback);
  if (p.documenting()) return 0;
  const int index = materialIndex(name);
  if (index < 0) {
    std::string valid;
    for (const Material& m : materials_)
      if (m.name != kRigidMaterial || !m.isBuiltInRigid) valid += (valid.empty() ? "" : ", ") + m.name;
    p.fail(k.name, "'" + name + "'", "one of the materials: " + valid + " (walls may also use 'rigid')");
  }
  return index;
}

ContactTable::ContactTable(Params& root) {
  materials_ = readMaterials(root);
  addRigidMaterial();
  count_ = static_cast<int>(materials_.size());
  Params c = root.section({"contact", "-", "contact model (laws by name) and per-pair interaction parameters"});
  lawModel_ = Registry<ContactLawModel>::instance().create(
      c, {"law", "-", "normal/tangential contact law"}, "hertz_mindlin");
  auto rolling = Registry<RollingModel>::instance().create(c, {"rolling", "-", "rolling resistance model"}, "none");
  auto cohesion = Registry<CohesionModel>::instance().create(c, {"cohesion", "-", "cohesion model"}, "none");
  normalLaw_ = lawModel_->law();
  rollingLaw_ = rolling->law();
  cohesionLaw_ = cohesion->law();
  rollingDamping_ = rolling->dampingRatio();
  const PairProperties defaults = readPairProperties(c, PairProperties{});
  table_.assign(static_cast<std::size_t>(count_) * static_cast<std::size_t>(count_), PairCoefficients{});
  for (int a = 0; a < count_; ++a)
    for (int b = 0; b < count_; ++b) computePair(a, b, materialPair(materials_[a], materials_[b], defaults));
  for (Params& pp : c.list({"pairs", "-", "parameters of specific material pairs (override the defaults above)"})) {
    const int a = readMaterial(pp, {"material_a", "-", "first material of the pair"});
    const int b = readMaterial(pp, {"material_b", "-", "second material of the pair"});
    if (pp.documenting()) {
      readPairProperties(pp, defaults);
      continue;
    }
    const PairProperties q = readPairProperties(pp, materialPair(materials_[a], materials_[b], defaults));
    computePair(a, b, q);
    computePair(b, a, q);
  }
}

void ContactTable::computePair(int a, int b, const PairProperties& p) {
  PairCoefficients& c = table_[a * count_ + b];
  c = PairCoefficients{};
  c.effectiveYoungs = effectiveYoungs(materials_[a], materials_[b]);
  c.effectiveShear = effectiveShear(materials_[a], materials_[b]);
  c.friction = p.friction;
  c.rollingFriction = p.rollingFriction;
  c.cohesionEnergyDensity = p.cohesionEnergyDensity;
  c.restitution = p.restitution;
  c.rollingDamping = rollingDamping_;
  lawModel_->fill(c, materials_[a], materials_[b], p);
}

void ContactTable::configure(std::vector<Material> materials, NormalLaw law, RollingLaw rolling,
                             CohesionLaw cohesion, const PairProperties& allPairs, double hookeStiffness,
                             double rollingDamping) {
  materials_ = std::move(materials);
  addRigidMaterial();
  count_ = static_cast<int>(materials_.size());
  normalLaw_ = law;
  rollingLaw_ = rolling;
  cohesionLaw_ = cohesion;
  rollingDamping_ = rollingDamping;
  Params p = Params::loadString(fmt::format("normal_stiffness: {}\n", hookeStiffness), "(configure)");
  lawModel_ = Registry<ContactLawModel>::instance().createByName(
      law == NormalLaw::Hooke ? "hooke" : "hertz_mindlin", p);
  table_.assign(static_cast<std::size_t>(count_) * static_cast<std::size_t>(count_), PairCoefficients{});
  for (int a = 0; a < count_; ++a)
    for (int b = 0; b < count_; ++b) computePair(a, b, allPairs);
}

}  // namespace gf::dem
