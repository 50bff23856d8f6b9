// Discrete diameters with mass fractions; number weights w_k = f_k / d_k^3.
#include <algorithm>

#include "dem/insertion/size_distribution.hpp"

namespace gf::dem {
namespace {
class DiscreteSize final : public SizeDistribution {
 public:
  explicit DiscreteSize(Params& p) {
    diameters_ = p.reals({"diameters", "m", "discrete: list of diameters", Range::positive()}, {0.002});
    std::vector<double> fractions =
        p.reals({"mass_fractions", "-", "discrete: mass fraction of each diameter (normalised)", Range::nonNegative()},
                {1.0});
    if (p.documenting()) fractions.assign(diameters_.size(), 1.0);
    if (fractions.size() != diameters_.size())
      p.fail("mass_fractions", std::to_string(fractions.size()) + " values",
             std::to_string(diameters_.size()) + " values (one per diameter)");
    double total = 0.0;
    for (std::size_t k = 0; k < diameters_.size(); ++k) {
      const double w = fractions[k] / (diameters_[k] * diameters_[k] * diameters_[k]);
      total += w;
      cumulative_.push_back(total);
    }
    if (!(total > 0.0)) p.fail("mass_fractions", "all zero", "at least one positive fraction");
    for (double& c : cumulative_) c /= total;
  }
  double sample(Random& rng) const override {
    const double u = rng.uniform();
    for (std::size_t k = 0; k < cumulative_.size(); ++k)
      if (u < cumulative_[k]) return diameters_[k];
    return diameters_.back();
  }
  double maxDiameter() const override { return *std::max_element(diameters_.begin(), diameters_.end()); }
  double minDiameter() const override {  // of the diameters that can be drawn (a positive fraction)
    double smallest = maxDiameter();
    for (std::size_t k = 0; k < diameters_.size(); ++k)
      if (cumulative_[k] > (k == 0 ? 0.0 : cumulative_[k - 1])) smallest = std::min(smallest, diameters_[k]);
    return smallest;
  }

 private:
  std::vector<double> diameters_, cumulative_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::SizeDistribution, gf::dem::DiscreteSize, "discrete",
                  "discrete diameters with mass fractions")
