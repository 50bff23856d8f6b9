#pragma once
// Shared set-up for the coupling tests: grids, particle sets, fluid fields, a Coupler from YAML.
#include <array>
#include <memory>
#include <random>
#include <string>

#include "core/coupling_fields.hpp"
#include "core/params.hpp"
#include "coupling/coupler.hpp"
#include "dem/particles.hpp"

namespace gf::coupling::testing {

inline CartesianGrid makeGrid(std::array<int, 3> n, Vec3 spacing, Vec3 origin = {}) {
  CartesianGrid g;
  g.origin = origin;
  g.spacing = spacing;
  g.cells = n;
  g.ghosts = 2;
  return g;
}

/// `count` particles of radius in [rMin, rMax], centres uniformly in [lo, hi] (may reach over walls).
inline dem::ParticleSet randomParticles(int count, double rMin, double rMax, Vec3 lo, Vec3 hi, unsigned seed = 7) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  dem::ParticleSet s;
  for (int i = 0; i < count; ++i) {
    const Vec3 x{lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y), lo.z + u(rng) * (hi.z - lo.z)};
    const Vec3 v{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
    const Vec3 w{10 * (u(rng) - 0.5), 10 * (u(rng) - 0.5), 10 * (u(rng) - 0.5)};
    s.add(i, 0, rMin + u(rng) * (rMax - rMin), 2500.0, x, v, w);
  }
  return s;
}

/// Coupler from a `coupling:` section given as YAML lines (indented by the caller).
inline std::unique_ptr<Coupler> makeCoupler(const std::string& couplingBody, const CartesianGrid& grid,
                                            std::array<bool, 3> periodic = {false, false, false},
                                            Vec3 gravity = {0.0, 0.0, -9.81},
                                            ExchangeModel model = ExchangeModel::A) {
  Params p = Params::loadString("coupling:\n" + couplingBody, "test.yaml");
  auto c = std::make_unique<Coupler>(p, grid, periodic, gravity, model);
  p.checkUnknownKeys();
  return c;
}

/// Cell-centred fluid fields filled from a function of the cell centre.
struct FluidFields {
  Field u[3], gradP[3];
  explicit FluidFields(const CartesianGrid& g) {
    for (int a = 0; a < 3; ++a) {
      u[a] = Field(g);
      gradP[a] = Field(g);
    }
  }
  template <class Fn>
  void setVelocity(const CartesianGrid& g, Fn&& fn) {
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i) {
          const Vec3 v = fn(g.cellCentre(i, j, k));
          for (int a = 0; a < 3; ++a) u[a](i, j, k) = v[a];
        }
  }
  template <class Fn>
  void setPressureGradient(const CartesianGrid& g, Fn&& fn) {
    for (int k = 0; k < g.cells[2]; ++k)
      for (int j = 0; j < g.cells[1]; ++j)
        for (int i = 0; i < g.cells[0]; ++i) {
          const Vec3 v = fn(g.cellCentre(i, j, k));
          for (int a = 0; a < 3; ++a) gradP[a](i, j, k) = v[a];
        }
  }
  FluidView view(double density, double viscosity, double dt = 1e-3) const {
    FluidView v;
    for (int a = 0; a < 3; ++a) {
      v.velocity[a] = &u[a];
      v.pressureGradient[a] = &gradP[a];
    }
    v.density = density;
    v.viscosity = viscosity;
    v.timeStep = dt;
    return v;
  }
};

/// sum over interior cells of (1 - eps) V_c.
inline double solidVolume(const Field& eps) {
  const CartesianGrid& g = eps.grid();
  double s = 0.0;
  for (int k = 0; k < g.cells[2]; ++k)
    for (int j = 0; j < g.cells[1]; ++j)
      for (int i = 0; i < g.cells[0]; ++i) s += (1.0 - eps(i, j, k)) * g.cellVolume();
  return s;
}

}  // namespace gf::coupling::testing
