// Linear spring-dashpot with tangential history (seed 000 eq. B.5): registration and coefficients.
#include "dem/contact/hooke.hpp"

#include "dem/contact/contact_law.hpp"
#include "dem/contact/restitution_damping.hpp"

namespace gf::dem {
namespace {

class HookeModel final : public ContactLawModel {
 public:
  explicit HookeModel(Params& p)
      : normalStiffness_(p.real({"normal_stiffness", "N/m", "hooke: normal spring constant k_n", Range::positive()},
                                1e4)),
        tangentialRatio_(p.real({"tangential_stiffness_ratio", "-", "hooke: k_t / k_n (2/7 matches the normal and "
                                 "tangential oscillation periods of a sphere)", Range::positive()},
                                2.0 / 7.0)) {}
  NormalLaw law() const override { return NormalLaw::Hooke; }
  void fill(PairCoefficients& c, const Material&, const Material&, const PairProperties& p) const override {
    c.normalStiffness = normalStiffness_;
    c.tangentialStiffness = tangentialRatio_ * normalStiffness_;
    c.damping = dampingForRestitution(p.restitution, 1.0, 0.0);
    c.tangentialDampingRatio = std::sqrt(tangentialRatio_);
  }

 private:
  double normalStiffness_;
  double tangentialRatio_;
};

}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::ContactLawModel, gf::dem::HookeModel, "hooke",
                  "linear spring-dashpot with tangential history and Coulomb limit (seed 000 eq. B.5)")
