// Monodisperse particles.
#include "dem/insertion/size_distribution.hpp"

namespace gf::dem {
namespace {
class ConstantSize final : public SizeDistribution {
 public:
  explicit ConstantSize(Params& p)
      : diameter_(p.real({"diameter", "m", "constant: particle diameter", Range::positive()}, 0.002)) {}
  double sample(Random&) const override { return diameter_; }
  double maxDiameter() const override { return diameter_; }
  double minDiameter() const override { return diameter_; }

 private:
  double diameter_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::SizeDistribution, gf::dem::ConstantSize, "constant", "one diameter")
