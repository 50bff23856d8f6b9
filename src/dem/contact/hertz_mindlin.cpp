// Hertz-Mindlin with tangential history: registration and per-pair coefficients.
#include "dem/contact/hertz_mindlin.hpp"

#include "dem/contact/contact_law.hpp"
#include "dem/contact/restitution_damping.hpp"

namespace gf::dem {
namespace {

class HertzMindlinModel final : public ContactLawModel {
 public:
  explicit HertzMindlinModel(Params&) {}
  NormalLaw law() const override { return NormalLaw::HertzMindlin; }
  void fill(PairCoefficients& c, const Material&, const Material&, const PairProperties& p) const override {
    c.damping = dampingForRestitution(p.restitution, 1.5, 0.25);
    // gamma_t / gamma_n = sqrt(k_t / (dF_n/dd)) = sqrt(8 G* / (2 E*)).
    c.tangentialDampingRatio = std::sqrt(4.0 * c.effectiveShear / c.effectiveYoungs);
  }
};

}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::ContactLawModel, gf::dem::HertzMindlinModel, "hertz_mindlin",
                  "Hertz normal force, Mindlin tangential spring with history and Coulomb limit, damping from e")
