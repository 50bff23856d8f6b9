#include "coupling/void_fraction/void_fraction_scheme.hpp"

#include <algorithm>

namespace gf::coupling {

double maxRadius(const dem::ParticleSet& particles) {
  double r = 0.0;
  for (double ri : particles.radius) r = std::max(r, ri);
  return r;
}

}  // namespace gf::coupling
