// No rolling resistance.
#include "dem/contact/contact_law.hpp"

namespace gf::dem {
namespace {
class NoRolling final : public RollingModel {
 public:
  explicit NoRolling(Params&) {}
  RollingLaw law() const override { return RollingLaw::None; }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::RollingModel, gf::dem::NoRolling, "none", "no rolling resistance")
