// Elastic-plastic spring-dashpot rolling resistance (Ai et al. 2011 model C).
#include "dem/contact/contact_law.hpp"

namespace gf::dem {
namespace {
class EpsdRolling final : public RollingModel {
 public:
  explicit EpsdRolling(Params& p)
      : damping_(p.real({"rolling_damping_ratio", "-", "epsd: viscous damping ratio eta_r of the rolling spring",
                         Range::nonNegative()},
                        0.3)) {}
  RollingLaw law() const override { return RollingLaw::Epsd; }
  double dampingRatio() const override { return damping_; }

 private:
  double damping_;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::RollingModel, gf::dem::EpsdRolling, "epsd",
                  "elastic-plastic spring-dashpot rolling torque (Ai et al. 2011, model C)")
