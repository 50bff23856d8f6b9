#include "coupling/drag/yin_sundaresan.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
namespace {
class YinSundaresanDrag final : public DragLaw {
 public:
  explicit YinSundaresanDrag(Params&) {}
  void evaluate(std::size_t n, const double* re, const double* eps, double* f) const override {
    for (std::size_t i = 0; i < n; ++i) f[i] = correction(re[i], eps[i]);
  }
  double correction(double re, double eps) const override { return drag::yinSundaresan(eps, 1.0, re); }
  bool polydisperse() const override { return true; }
  double polydisperseCorrection(double, double eps, double sizeRatio, double mixtureReynolds) const override {
    return drag::yinSundaresan(eps, sizeRatio, mixtureReynolds);
  }
};
}  // namespace
GF_REGISTER_MODEL(DragLaw, YinSundaresanDrag, "yin_sundaresan",
                  "Yin & Sundaresan (2009) polydisperse with the mixture Reynolds number of Holloway et al. (2010) "
                  "(seed 003 eqs. 3.21-3.24, 3.28): F*_i = 1/eps + (F*(phi, Re_mix) - 1/eps)(a y_i + (1 - a) y_i^2)")
}  // namespace gf::coupling
