#pragma once
// Helpers for the fluid tests: build a solver from an inline case text.
#include <memory>
#include <string>

#include "core/domain.hpp"
#include "core/params.hpp"
#include "fluid/solver.hpp"

namespace gf::fluid::test {

struct Case {
  Params params;
  Domain domain;
  std::unique_ptr<Solver> solver;
};

inline Case makeCase(const std::string& yaml, const Vec3& gravity = Vec3{}) {
  Case c{Params::loadString(yaml, "test.yaml"), Domain{}, nullptr};
  c.domain = Domain::read(c.params);
  c.solver = std::make_unique<Solver>(c.params, c.domain, gravity);
  c.params.checkUnknownKeys();
  return c;
}

/// Max |u_c - exact| over the interior faces of component c.
template <class Exact>
double maxFaceError(const Solver& s, int c, Exact&& exact) {
  const Field& u = s.velocity(c);
  const auto& g = s.grid();
  double e = 0.0;
  const auto& pts = u.points();
  for (int k = 0; k < pts[2]; ++k)
    for (int j = 0; j < pts[1]; ++j)
      for (int i = 0; i < pts[0]; ++i) {
        Vec3 x = g.cellCentre(i, j, k);
        x[c] -= 0.5 * g.spacing[c];
        e = std::max(e, std::abs(u(i, j, k) - exact(x)));
      }
  return e;
}

}  // namespace gf::fluid::test
