#pragma once
// Initial fluid fields read from the case file (section fluid.initial):
//   type: uniform       velocity, pressure (and scalar) constant in space (the default);
//   type: taylor_green  the 2D Taylor-Green vortex in the x-y plane added to the uniform fields:
//                       u =  U0 sin(k x) cos(k y),  v = -U0 cos(k x) sin(k y),  w = 0,
//                       p = p0 + rho U0^2 / 4 (cos 2kx + cos 2ky),  k = 2 pi / wavelength
//                       (Taylor & Green 1937). At rest otherwise it is an exact solution of the
//                       Navier-Stokes equations that decays as exp(-2 nu k^2 t) (velocity),
//                       exp(-4 nu k^2 t) (kinetic energy): the fluid solver's order-of-accuracy
//                       test (validation/fluid_taylor_green_*). Coordinates are absolute, so a
//                       periodic box [0, wavelength] x [0, wavelength] holds one vortex cell pair.
#include <cmath>
#include <functional>

#include "core/params.hpp"
#include "core/vec3.hpp"

namespace gf::fluid {

struct InitialCondition {
  std::function<Vec3(const Vec3&)> velocity;
  std::function<double(const Vec3&)> pressure;
  double scalar = 0.0;
};

/// Reads the keys of `init` (the fluid.initial section); `density` enters the Taylor-Green pressure.
InitialCondition readInitialCondition(Params& init, double density);

/// Taylor-Green velocity of amplitude u0 and wavenumber k at x (Taylor & Green 1937).
inline Vec3 taylorGreenVelocity(const Vec3& x, double u0, double k) {
  return Vec3{u0 * std::sin(k * x.x) * std::cos(k * x.y), -u0 * std::cos(k * x.x) * std::sin(k * x.y), 0.0};
}

/// Taylor-Green pressure (without the constant): rho u0^2 / 4 (cos 2kx + cos 2ky).
inline double taylorGreenPressure(const Vec3& x, double u0, double k, double density) {
  return 0.25 * density * u0 * u0 * (std::cos(2.0 * k * x.x) + std::cos(2.0 * k * x.y));
}

}  // namespace gf::fluid
