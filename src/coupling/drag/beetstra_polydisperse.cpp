#include "coupling/drag/beetstra_polydisperse.hpp"

#include "coupling/drag/drag_law.hpp"

namespace gf::coupling {
namespace {
class BeetstraPolydisperseDrag final : public DragLaw {
 public:
  explicit BeetstraPolydisperseDrag(Params&) {}
  void evaluate(std::size_t n, const double* re, const double* eps, double* f) const override {
    for (std::size_t i = 0; i < n; ++i) f[i] = correction(re[i], eps[i]);
  }
  double correction(double re, double eps) const override { return drag::beetstraPolydisperse(re, eps, 1.0); }
  bool polydisperse() const override { return true; }
  double polydisperseCorrection(double re, double eps, double sizeRatio, double) const override {
    return drag::beetstraPolydisperse(re, eps, sizeRatio);
  }
};
}  // namespace
GF_REGISTER_MODEL(DragLaw, BeetstraPolydisperseDrag, "beetstra_polydisperse",
                  "Beetstra, van der Hoef & Kuipers (2007) polydisperse (seed 003 eq. 3.20): F*_i = [eps y_i + phi "
                  "y_i^2 + 0.064 eps y_i^3] F*(phi, <Re>), y_i = d_i/<d>, <d> the Sauter mean diameter of the cell")
}  // namespace gf::coupling
