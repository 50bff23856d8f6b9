// Rosin-Rammler (Weibull) distribution by MASS: mass fraction finer than d is
// F(d) = 1 - exp(-(d/d63)^n) (Rosin & Rammler 1933). Sampled by number: d from the mass
// distribution (inverse CDF, truncated to [min, max]), accepted with probability (min/d)^3.
#include <cmath>

#include "dem/insertion/size_distribution.hpp"

namespace gf::dem {
namespace {
class RosinRammlerSize final : public SizeDistribution {
 public:
  explicit RosinRammlerSize(Params& p) {
    d63_ = p.real({"characteristic_diameter", "m", "rosin_rammler: d63 (63.2 % of the mass finer)",
                   Range::positive()},
                  0.002);
    spread_ = p.real({"spread", "-", "rosin_rammler: uniformity exponent n", Range::positive()}, 3.0);
    min_ = p.real({"min_diameter", "m", "rosin_rammler: smallest diameter", Range::positive()}, 0.5 * d63_);
    max_ = p.real({"max_diameter", "m", "rosin_rammler: largest diameter", Range::positive()}, 1.5 * d63_);
    if (!p.documenting() && !(max_ > min_)) p.fail("max_diameter", "not above min_diameter", "max > min");
  }
  double sample(Random& rng) const override {
    const double fMin = massFractionBelow(min_), fMax = massFractionBelow(max_);
    for (int attempt = 0; attempt < 100000; ++attempt) {
      const double f = fMin + (fMax - fMin) * rng.uniform();
      const double d = d63_ * std::pow(-std::log(1.0 - f), 1.0 / spread_);
      const double accept = std::pow(min_ / d, 3.0);
      if (rng.uniform() < accept) return d;
    }
    return min_;
  }
  double maxDiameter() const override { return max_; }
  double minDiameter() const override { return min_; }

 private:
  double massFractionBelow(double d) const { return 1.0 - std::exp(-std::pow(d / d63_, spread_)); }
  double d63_, spread_, min_, max_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::SizeDistribution, gf::dem::RosinRammlerSize, "rosin_rammler",
                  "Rosin-Rammler by mass (characteristic_diameter d63, spread n), truncated")
