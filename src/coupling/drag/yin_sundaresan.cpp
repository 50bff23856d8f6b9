#include "coupling/drag/yin_sundaresan.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
namespace {
class YinSundaresanDrag final : public DragLaw {
 public:
  explicit YinSundaresanDrag(Params& p) {
    const bool friction = p.boolean({"fluid_mediated_friction", "-",
                                     "the fluid-mediated particle-particle friction between size classes of Yin & "
                                     "Sundaresan (2009), seed 003 eqs. 3.25-3.27 (a force between the classes of a "
                                     "cell, not exchanged with the fluid)"},
                                    false);
    const double cutoff = p.real({"lubrication_cutoff", "m",
                                  "lubrication cutoff length lambda of the friction factor alpha_ij = 1.313 "
                                  "log10(min(d_i, d_j)/lambda) - 1.249 (seed 003 eq. 3.27; lambda/d = 1e-3 ... 1e-2 "
                                  "in the fit)",
                                  Range::positive()},
                                 1e-7);
    cutoff_ = friction ? cutoff : 0.0;
  }
  void evaluate(std::size_t n, const double* re, const double* eps, double* f) const override {
    for (std::size_t i = 0; i < n; ++i) f[i] = correction(re[i], eps[i]);
  }
  double correction(double re, double eps) const override { return drag::yinSundaresan(eps, 1.0, re); }
  bool polydisperse() const override { return true; }
  double polydisperseCorrection(double, double eps, double sizeRatio, double mixtureReynolds) const override {
    return drag::yinSundaresan(eps, sizeRatio, mixtureReynolds);
  }
  double lubricationCutoff() const override { return cutoff_; }

 private:
  double cutoff_ = 0.0;
};
}  // namespace
GF_REGISTER_MODEL(DragLaw, YinSundaresanDrag, "yin_sundaresan",
                  "Yin & Sundaresan (2009) polydisperse with the mixture Reynolds number of Holloway et al. (2010) "
                  "(seed 003 eqs. 3.21-3.24, 3.28): F*_i = 1/eps + (F*(phi, Re_mix) - 1/eps)(a y_i + (1 - a) y_i^2)")
}  // namespace gf::coupling
