#pragma once
// Small portable random generator (SplitMix64, Steele et al. 2014): the same seed gives the same
// numbers on every platform and standard library (std:: distributions do not), and its whole
// state is one integer, so restarts continue the sequence exactly.
#include <cmath>
#include <cstdint>
#include <numbers>

namespace gf::dem {

class Random {
 public:
  explicit Random(std::uint64_t seed = 0) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Standard normal (Box-Muller).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  std::uint64_t state() const { return state_; }
  void setState(std::uint64_t s) { state_ = s; }

 private:
  std::uint64_t state_;
};

}  // namespace gf::dem
