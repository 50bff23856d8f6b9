// Log-normal number distribution: ln d ~ N(ln d50, sigma^2), truncated to [min, max].
#include <algorithm>
#include <cmath>

#include "dem/insertion/size_distribution.hpp"

namespace gf::dem {
namespace {
class LogNormalSize final : public SizeDistribution {
 public:
  explicit LogNormalSize(Params& p) {
    median_ = p.real({"median_diameter", "m", "log_normal: number median diameter d50", Range::positive()}, 0.002);
    sigma_ = p.real({"sigma", "-", "log_normal: standard deviation of ln d", Range::nonNegative()}, 0.1);
    min_ = p.real({"min_diameter", "m", "log_normal: smallest diameter (truncation)", Range::positive()},
                  median_ * std::exp(-3.0 * sigma_));
    max_ = p.real({"max_diameter", "m", "log_normal: largest diameter (truncation)", Range::positive()},
                  median_ * std::exp(3.0 * sigma_));
    if (!p.documenting() && !(max_ >= min_)) p.fail("max_diameter", "below min_diameter", "max >= min");
  }
  double sample(Random& rng) const override {
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const double d = median_ * std::exp(sigma_ * rng.normal());
      if (d >= min_ && d <= max_) return d;
    }
    return median_;
  }
  double maxDiameter() const override { return max_; }
  double minDiameter() const override { return std::min(min_, median_); }  // (d50: sample()'s fallback)

 private:
  double median_, sigma_, min_, max_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::SizeDistribution, gf::dem::LogNormalSize, "log_normal",
                  "log-normal by number (median_diameter, sigma), truncated")
