#include "fluid/initial_condition.hpp"

#include <numbers>

namespace gf::fluid {

InitialCondition readInitialCondition(Params& init, double density) {
  const Vec3 u0 = init.vec3({"velocity", "m/s", "uniform initial velocity (0 in blocked cells)"}, Vec3{});
  const double p0 = init.real({"pressure", "Pa", "uniform initial pressure"}, 0.0);
  const double s0 = init.real({"scalar", "-", "uniform initial passive scalar"}, 0.0);
  const std::string type = init.choice(
      {"type", "-", "uniform: the values above; taylor_green: a 2D Taylor-Green vortex in the x-y plane added to them (docs/fluid.md)"},
      {"uniform", "taylor_green"}, "uniform");
  const double amplitude =
      init.real({"amplitude", "m/s", "taylor_green: velocity amplitude U0 (u = U0 sin kx cos ky, v = -U0 cos kx sin ky)"}, 1.0);
  const double wavelength = init.real(
      {"wavelength", "m", "taylor_green: wavelength 2 pi / k in x and y (absolute coordinates)", Range::positive()},
      2.0 * std::numbers::pi);

  InitialCondition ic;
  ic.scalar = s0;
  if (type == "uniform") {
    ic.velocity = [u0](const Vec3&) { return u0; };
    ic.pressure = [p0](const Vec3&) { return p0; };
    return ic;
  }
  const double k = 2.0 * std::numbers::pi / wavelength;
  ic.velocity = [u0, amplitude, k](const Vec3& x) { return u0 + taylorGreenVelocity(x, amplitude, k); };
  ic.pressure = [p0, amplitude, k, density](const Vec3& x) { return p0 + taylorGreenPressure(x, amplitude, k, density); };
  return ic;
}

}  // namespace gf::fluid
