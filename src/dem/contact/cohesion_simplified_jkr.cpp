// Simplified JKR cohesion (see simplified_jkr.hpp).
#include "dem/contact/contact_law.hpp"

namespace gf::dem {
namespace {
class SimplifiedJkrCohesion final : public CohesionModel {
 public:
  explicit SimplifiedJkrCohesion(Params&) {}
  CohesionLaw law() const override { return CohesionLaw::SimplifiedJkr; }
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::CohesionModel, gf::dem::SimplifiedJkrCohesion, "simplified_jkr",
                  "attractive force k_c A in contact (LIGGGHTS sjkr); k_c = cohesion_energy_density of the pair")
