#pragma once
// Helpers for DEM tests: build a System from YAML text.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "dem/system.hpp"

namespace gf::dem::test {

struct DemCase {
  Params params;
  Domain domain;
  std::unique_ptr<System> system;
  DemCase(const std::string& yaml, const Vec3& gravity, InitialParticles initial = InitialParticles::Insert)
      : params(Params::loadString(yaml, "test.yaml")) {
    domain = Domain::read(params);
    system = std::make_unique<System>(params, domain, gravity, initial);
    params.checkUnknownKeys();
  }
  System& operator*() { return *system; }
  System* operator->() { return system.get(); }
};

/// One material 'glass' plus a contact section; `extra` is appended verbatim.
inline std::string materialsYaml(const std::string& law, double e, double mu, double youngs = 1e7, double nu = 0.3,
                                 const std::string& contactExtra = "") {
  return fmt::format(R"(
materials:
  - {{name: glass, density: 2500, youngs_modulus: {}, poisson_ratio: {}}}
contact:
  law: {}
  restitution: {}
  friction: {}
{}
)",
                     youngs, nu, law, e, mu, contactExtra);
}

}  // namespace gf::dem::test
