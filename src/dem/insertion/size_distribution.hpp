#pragma once
// Particle size distributions (by name: constant, discrete, log_normal, rosin_rammler), sampled
// by number with the seeded portable generator, so that the same case gives the same particles.
#include "core/params.hpp"
#include "core/registry.hpp"
#include "dem/random.hpp"

namespace gf::dem {

class SizeDistribution {
 public:
  virtual ~SizeDistribution() = default;
  /// A diameter drawn by number (m).
  virtual double sample(Random& rng) const = 0;
  /// Largest diameter the distribution can return (m).
  virtual double maxDiameter() const = 0;
  /// Smallest diameter the distribution can return (m): the time-step check uses it.
  virtual double minDiameter() const = 0;
};

/// Reads `size` (a section with `distribution: <name>` and that model's keys) from `p`.
std::unique_ptr<SizeDistribution> readSizeDistribution(Params& p);

}  // namespace gf::dem
