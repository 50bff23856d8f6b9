#pragma once
// Drag laws for unresolved CFD-DEM: one convention for all of them.
//
// Force of the fluid on ONE particle (drag part only, model-A sense: the mean pressure-gradient
// ("buoyancy") part -V_p grad p is a separate force, see docs/coupling.md):
//
//     F_d = beta_p (u_f - u_p),      beta_p = 3 pi mu d f(Re, eps)      [beta_p in kg/s]
//
//   u_f   interstitial (not superficial) fluid velocity at the particle, m/s
//   Re    = rho_f |u_f - u_p| d / mu : particle Reynolds number of the INTERSTITIAL slip (no eps)
//   eps   local void fraction
//   f     dimensionless drag correction relative to Stokes drag on the interstitial slip.
//         f = 1 for an isolated sphere in creeping flow.
//
// Each law computes the Reynolds number of its paper from (Re, eps): laws written for the
// superficial slip use Re_sup = eps * Re (Di Felice, Rong, Koch-Hill, Beetstra, Wen-Yu);
// Syamlal-O'Brien uses the interstitial Re. Laws given as a momentum exchange coefficient per
// volume of suspension beta_vol (N s/m^4, Gidaspow, Koch-Hill, Syamlal-O'Brien) are converted with
// F_d = beta_vol V_p / phi (u_f - u_p) (seed 000 eq. 5.14), i.e. f = beta_vol d^2 / (18 mu phi).
// Laws normalised with the superficial velocity (Beetstra F*) become f = eps F*.
//
// The DragLaw interface evaluates whole arrays (one virtual call per coupling step); each model is
// a pure inline function f(Re, eps) in its own header, shared by CPU loops and tests.
#include <cstddef>
#include <memory>

#include "coupling/loops.hpp"
#include "core/params.hpp"
#include "core/registry.hpp"

namespace gf::coupling {

/// A drag law as a pure function f(Re, eps).
using CorrectionFunction = double (*)(double reynolds, double voidFraction);

class DragLaw {
 public:
  virtual ~DragLaw() = default;
  /// The pure function behind the law, or nullptr if the law is not one (then use evaluate /
  /// correction). Lets a caller resolve the law once and run its own monomorphic loop.
  virtual CorrectionFunction function() const { return nullptr; }
  /// correction[i] = f(reynolds[i], voidFraction[i]) for i in [0, n).
  virtual void evaluate(std::size_t n, const double* reynolds, const double* voidFraction,
                        double* correction) const = 0;
  /// One value (tests, helpers; not for hot loops).
  virtual double correction(double reynolds, double voidFraction) const = 0;
  /// Whether the law needs the particle's size ratio and its cell's mixture Reynolds number
  /// (polydisperse laws, seed 003 sec. 3.1.3); the coupler then computes them (size_classes.hpp)
  /// and calls polydisperseCorrection. correction(Re, eps) is then the law of a monodisperse
  /// suspension (size ratio 1, the particle's own slip as the mixture slip).
  virtual bool polydisperse() const { return false; }
  /// f of a particle of size ratio y = d_i / <d> (<d> the Sauter mean diameter of its cell) at its
  /// own Re and eps, in a cell of mixture Reynolds number reMix = rho |u_f - <v>| <d> / mu
  /// (<v> the volume-weighted mean velocity of the cell's particles).
  virtual double polydisperseCorrection(double reynolds, double voidFraction, double sizeRatio,
                                        double mixtureReynolds) const {
    (void)sizeRatio, (void)mixtureReynolds;
    return correction(reynolds, voidFraction);
  }
  /// The lubrication cutoff length lambda (m) of the law's fluid-mediated particle-particle
  /// friction (yin_sundaresan with fluid_mediated_friction), 0 if it has none.
  virtual double lubricationCutoff() const { return 0.0; }
};

/// A DragLaw made from a pure function f(Re, eps); the loop over particles is monomorphic.
template <double (*Correction)(double, double)>
class DragLawOf final : public DragLaw {
 public:
  explicit DragLawOf(Params&) {}
  DragLawOf() = default;
  void evaluate(std::size_t n, const double* reynolds, const double* voidFraction,
                double* correction) const override {
    forEachIndex(static_cast<std::int64_t>(n), 8,
                 [&](std::int64_t i) { correction[i] = Correction(reynolds[i], voidFraction[i]); });
  }
  double correction(double reynolds, double voidFraction) const override {
    return Correction(reynolds, voidFraction);
  }
  CorrectionFunction function() const override { return Correction; }
};

/// Drag coefficient per particle, beta_p = 3 pi mu d f (kg/s).
inline double particleDragCoefficient(double viscosity, double diameter, double correction) {
  return 3.0 * 3.14159265358979323846 * viscosity * diameter * correction;
}

}  // namespace gf::coupling
