// Monitor "mixing_layer": width of the particle-fluid mixing layer of a Rayleigh-Taylor instability
// (a suspension layer, the "heavy fluid", above particle-free fluid), seed 001 sec. 3.3 (lines 375-424).
//
// The solid fraction is averaged over each cell layer normal to `axis` (from the coupling's void
// fraction field). phi0 is the layer-average solid fraction of the suspension at the first sample
// (the mean over the layers holding more than half the densest layer). Fronts (seed 001 line 409:
// "from the first position where we have the diluted region of particles and ending with the last
// denser layer having less particles than the initial packing"):
//   lower_front  centre of the lowest layer with phi > threshold phi0        (spikes falling)
//   upper_front  centre of the highest layer with phi < (1 - threshold) phi0, searched downwards
//                from the top of the initial suspension                        (bubbles rising)
//   mixing_width h = upper_front - lower_front
// Growth law after the initial exponential phase (seed 001 eq. 42-43): h = alpha A g t^2,
//   A = (rho_mix - rho_f) / (rho_mix + rho_f), rho_mix = (1 - phi0) rho_f + phi0 rho_p.
//   alpha        least-squares slope of h against A g t^2 over the samples with fit_start <= t
//                (with an intercept, so the width reached by the end of the exponential phase
//                does not bias the slope); 0 before two such samples exist.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/monitor.hpp"
#include "dem/system.hpp"
#include "fluid/solver.hpp"

namespace gf::coupling {
namespace {

class MixingLayerMonitor final : public Monitor {
 public:
  explicit MixingLayerMonitor(Params& p) {
    const std::string a =
        p.choice({"axis", "-", "mixing_layer: vertical axis, pointing against gravity"}, {"x", "y", "z"}, "z");
    axis_ = a[0] - 'x';
    threshold_ = p.real({"threshold", "-", "mixing_layer: front criterion as a fraction of the initial solid fraction",
                         Range::between(0.01, 0.5)},
                        0.1);
    fitStart_ = p.real({"fit_start", "s", "mixing_layer: first time of the alpha fit (end of the exponential phase)",
                        Range::atLeast(0.0)},
                       0.2);
  }
  std::vector<MonitorColumn> columns() const override {
    return {{"mixing_width", "m"}, {"lower_front", "m"}, {"upper_front", "m"}, {"atwood_number", "-"}, {"alpha", "-"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem || !s.fluid || s.dem->particles().size() == 0) return {0, 0, 0, 0, 0};
    const std::vector<double> phi = layerSolidFraction(*s.fluid);
    const CartesianGrid& g = s.fluid->grid();
    const int layers = static_cast<int>(phi.size());
    if (!initialised_) initialise(phi, s);
    int lowest = layers - 1, highest = 0;
    for (int l = 0; l < layers; ++l)
      if (phi[l] > threshold_ * phi0_) {
        lowest = l;
        break;
      }
    for (int l = topLayer_; l >= 0; --l)
      if (phi[l] < (1.0 - threshold_) * phi0_) {
        highest = l;
        break;
      }
    const double dz = g.spacing[axis_];
    const double lower = g.origin[axis_] + (lowest + 0.5) * dz, upper = g.origin[axis_] + (highest + 0.5) * dz;
    const double width = std::max(0.0, upper - lower);
    if (s.time >= fitStart_) accumulateFit(atwood_ * gravity_ * s.time * s.time, width);
    return {width, lower, upper, atwood_, alpha()};
  }
  void save(BinaryWriter& out) const override {
    out.put(initialised_);
    out.put(phi0_);
    out.put(atwood_);
    out.put(gravity_);
    out.put(topLayer_);
    for (double v : fit_) out.put(v);
  }
  void load(BinaryReader& in) override {
    initialised_ = in.get<bool>();
    phi0_ = in.get<double>();
    atwood_ = in.get<double>();
    gravity_ = in.get<double>();
    topLayer_ = in.get<int>();
    for (double& v : fit_) v = in.get<double>();
  }

 private:
  std::vector<double> layerSolidFraction(const fluid::Solver& f) const {
    const CartesianGrid& g = f.grid();
    const Field& eps = f.couplingFields().voidFraction;
    const int a = axis_, b = (axis_ + 1) % 3, c = (axis_ + 2) % 3;
    std::vector<double> phi(g.cells[a], 0.0);
    int idx[3];
    for (int l = 0; l < g.cells[a]; ++l) {
      double sum = 0.0;
      idx[a] = l;
      for (int m = 0; m < g.cells[b]; ++m)
        for (int n = 0; n < g.cells[c]; ++n) {
          idx[b] = m;
          idx[c] = n;
          sum += 1.0 - eps(idx[0], idx[1], idx[2]);
        }
      phi[l] = sum / (double(g.cells[b]) * g.cells[c]);
    }
    return phi;
  }
  void initialise(const std::vector<double>& phi, const RunState& s) {
    const double densest = *std::max_element(phi.begin(), phi.end());
    double sum = 0.0;
    int count = 0;
    topLayer_ = 0;
    for (int l = 0; l < static_cast<int>(phi.size()); ++l)
      if (phi[l] > 0.5 * densest) {
        sum += phi[l];
        ++count;
        topLayer_ = l;
      }
    phi0_ = count > 0 ? sum / count : 0.0;
    const dem::ParticleSet& p = s.dem->particles();
    double mass = 0.0, volume = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      mass += p.mass[i];
      volume += 4.0 / 3.0 * std::numbers::pi * p.radius[i] * p.radius[i] * p.radius[i];
    }
    const double rhoP = mass / volume, rhoF = s.fluid->density();
    const double rhoMix = (1.0 - phi0_) * rhoF + phi0_ * rhoP;  // seed 001 eq. 43
    atwood_ = (rhoMix - rhoF) / (rhoMix + rhoF);
    gravity_ = std::abs(s.gravity[axis_]);
    initialised_ = true;
  }
  // Sums n, x, y, xx, xy of the linear fit width = alpha x + c, x = A g t^2.
  void accumulateFit(double x, double y) {
    fit_[0] += 1.0;
    fit_[1] += x;
    fit_[2] += y;
    fit_[3] += x * x;
    fit_[4] += x * y;
  }
  double alpha() const {
    const double n = fit_[0], det = n * fit_[3] - fit_[1] * fit_[1];
    return n >= 2.0 && det > 0.0 ? (n * fit_[4] - fit_[1] * fit_[2]) / det : 0.0;
  }

  int axis_ = 2;
  double threshold_ = 0.1, fitStart_ = 0.2;
  bool initialised_ = false;
  double phi0_ = 0.0, atwood_ = 0.0, gravity_ = 9.81;
  int topLayer_ = 0;
  double fit_[5] = {0, 0, 0, 0, 0};
};

}  // namespace
}  // namespace gf::coupling

GF_REGISTER_MODEL(gf::Monitor, gf::coupling::MixingLayerMonitor, "mixing_layer",
                  "Rayleigh-Taylor mixing-layer width of a suspension layer above clear fluid, and the growth "
                  "coefficient alpha of h = alpha A g t^2 (seed 001 eq. 42)")
