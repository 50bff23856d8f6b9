#include "coupling/void_fraction/void_fraction_scheme.hpp"

#include <algorithm>

#include "coupling/loops.hpp"

namespace gf::coupling {
namespace {

/// max(0, r[0..n)) with std::max's rule (a < b ? b : a: NaN entries are skipped), eight running
/// maxima side by side instead of one serial chain; the maximum does not depend on the order in
/// which it is taken, so the result is that of the serial loop.
GF_VECTOR_CLONES
double maxOf(const double* r, std::size_t n) {
  using Double8 = double __attribute__((vector_size(64)));
  Double8 m8{};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    Double8 v;
    __builtin_memcpy(&v, r + i, sizeof v);
    m8 = m8 < v ? v : m8;
  }
  double m = 0.0;
  for (int k = 0; k < 8; ++k) m = std::max(m, m8[k]);
  for (; i < n; ++i) m = std::max(m, r[i]);
  return m;
}

}  // namespace

double maxRadius(const dem::ParticleSet& particles) { return maxOf(particles.radius.data(), particles.radius.size()); }

}  // namespace gf::coupling
