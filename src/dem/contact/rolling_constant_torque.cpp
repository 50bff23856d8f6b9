// Constant directional torque rolling resistance (Ai et al. 2011 model A).
#include "dem/contact/contact_law.hpp"

namespace gf::dem {
namespace {
class ConstantTorqueRolling final : public RollingModel {
 public:
  explicit ConstantTorqueRolling(Params&) {}
  RollingLaw law() const override { return RollingLaw::ConstantTorque; }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::RollingModel, gf::dem::ConstantTorqueRolling, "constant_torque",
                  "constant directional torque M = -mu_r R* F_n w/|w| (Ai et al. 2011, model A)")
