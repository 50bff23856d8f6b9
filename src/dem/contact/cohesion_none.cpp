// No cohesion.
#include "dem/contact/contact_law.hpp"

namespace gf::dem {
namespace {
class NoCohesion final : public CohesionModel {
 public:
  explicit NoCohesion(Params&) {}
  CohesionLaw law() const override { return CohesionLaw::None; }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::CohesionModel, gf::dem::NoCohesion, "none", "no cohesion")
