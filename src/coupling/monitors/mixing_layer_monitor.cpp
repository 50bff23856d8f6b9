// Monitor "mixing_layer": width of the particle-fluid mixing layer of a Rayleigh-Taylor instability
// (a suspension layer, the "heavy fluid", above particle-free fluid), seed 001 sec. 3.3 (lines 375-424).
//
// The solid fraction phi is averaged over each cell layer normal to `axis` (from the coupling's void
// fraction field), then over `smoothing_layers` neighbouring layers (a running mean: a layer of a few
// hundred particles fluctuates by several per cent). The first sample fixes the initial profile
// phi_init and phi0, the mean of phi_init over the suspension (layers above half the densest).
// Fronts (seed 001 line 409: "from the first position where we have the diluted region of particles
// and ending with the last denser layer having less particles than the initial packing"):
//   lower_front  centre of the lowest layer with phi > threshold phi0              (spikes falling)
//   upper_front  going up from the lower front, centre of the last layer with
//                phi < (1 - threshold) phi_init before a layer of the initial suspension that
//                still holds its initial packing                                    (bubbles rising)
//   mixing_width h = upper_front - lower_front (the initial interface has h ~ 0)
// Searching upwards from the mixing zone (not down from the top) keeps the clear layer that
// opens under a closed lid as the suspension settles from counting as mixing.
// Growth law after the initial exponential phase (seed 001 eq. 42-43): h = alpha A g t^2,
//   A = (rho_mix - rho_f) / (rho_mix + rho_f), rho_mix = (1 - phi0) rho_f + phi0 rho_p.
//   alpha        least-squares slope of h against A g t^2 over the samples with
//                fit_start <= t <= fit_end (with an intercept, so the width reached by the end of
//                the exponential phase does not bias the slope); 0 before two such samples exist.
//   alpha_bubble, alpha_spike  the same for the distances the bubble (upper) and spike (lower)
//                fronts travel from the initial interface, h_b = alpha_b A g t^2 and
//                h_s = alpha_s A g t^2, the split used by the RT literature the seed cites
//                (Dimonte et al. 2004: alpha_b = 0.025-0.08, alpha_s / alpha_b growing with A);
//                alpha = alpha_b + alpha_s. The slopes need no interface position.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/monitor.hpp"
#include "dem/system.hpp"
#include "fluid/solver.hpp"
#include "parallel/exchange.hpp"

namespace gf::coupling {
namespace {

/// Least-squares line y = slope x + c from running sums (n, x, y, xx, xy).
struct LinearFit {
  double sums[5] = {0, 0, 0, 0, 0};
  void add(double x, double y) {
    sums[0] += 1.0;
    sums[1] += x;
    sums[2] += y;
    sums[3] += x * x;
    sums[4] += x * y;
  }
  double slope() const {
    const double n = sums[0], det = n * sums[3] - sums[1] * sums[1];
    return n >= 2.0 && det > 0.0 ? (n * sums[4] - sums[1] * sums[2]) / det : 0.0;
  }
};

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
    fitEnd_ = p.real({"fit_end", "s", "mixing_layer: last time of the alpha fit (before the fronts reach the walls)",
                      Range::positive()},
                     1e30);
    smoothing_ = static_cast<int>(p.integer(
        {"smoothing_layers", "-", "mixing_layer: layers in the running mean of the solid-fraction profile (odd)",
         Range::atLeast(1)},
        3));
    if (smoothing_ % 2 == 0) p.fail("smoothing_layers", std::to_string(smoothing_), "an odd number of layers");
  }
  std::vector<MonitorColumn> columns() const override {
    return {{"mixing_width", "m"}, {"lower_front", "m"}, {"upper_front", "m"}, {"atwood_number", "-"},
            {"alpha", "-"},        {"alpha_bubble", "-"}, {"alpha_spike", "-"}};
  }
  std::vector<double> sample(const RunState& s) override {
    if (!s.dem || !s.fluid) return {0, 0, 0, 0, 0, 0, 0};
    const std::vector<double> layerFractions = layerSolidFraction(*s.fluid);  // (collective under MPI)
    // (under MPI rank 0 holds every particle and writes the file; the others return zeros)
    if (monitoredParticles(s).size() == 0) return {0, 0, 0, 0, 0, 0, 0};
    const std::vector<double> phi = smoothed(layerFractions);
    const CartesianGrid& g = s.fluid->globalGrid();
    const int layers = static_cast<int>(phi.size());
    if (!initialised_) initialise(phi, s);
    int lower = layers - 1;
    for (int l = 0; l < layers; ++l)
      if (phi[l] > threshold_ * phi0_) {
        lower = l;
        break;
      }
    // Upwards from the lower front, the mixing zone ends below the first layer of the initial
    // suspension that still holds its initial packing.
    int upper = std::max(lower, bottomLayer_ - 1);
    for (int l = std::max(lower, bottomLayer_); l <= topLayer_; ++l) {
      if (phi[l] >= (1.0 - threshold_) * phiInit_[l]) break;
      upper = l;
    }
    const double dz = g.spacing[axis_];
    const double lowerFront = g.origin[axis_] + (lower + 0.5) * dz, upperFront = g.origin[axis_] + (upper + 0.5) * dz;
    const double width = upperFront - lowerFront;
    if (s.time >= fitStart_ && s.time <= fitEnd_) {
      const double x = atwood_ * gravity_ * s.time * s.time;
      width_.add(x, width);
      bubble_.add(x, upperFront);
      spike_.add(x, -lowerFront);
    }
    return {width, lowerFront, upperFront, atwood_, width_.slope(), bubble_.slope(), spike_.slope()};
  }
  void save(BinaryWriter& out) const override {
    out.put(initialised_);
    out.put(phi0_);
    out.put(atwood_);
    out.put(gravity_);
    out.put(topLayer_);
    out.put(bottomLayer_);
    out.putVector(phiInit_);
    for (const LinearFit* f : {&width_, &bubble_, &spike_})
      for (double v : f->sums) out.put(v);
  }
  void load(BinaryReader& in) override {
    initialised_ = in.get<bool>();
    phi0_ = in.get<double>();
    atwood_ = in.get<double>();
    gravity_ = in.get<double>();
    topLayer_ = in.get<int>();
    bottomLayer_ = in.get<int>();
    phiInit_ = in.getVector<double>();
    for (LinearFit* f : {&width_, &bubble_, &spike_})
      for (double& v : f->sums) v = in.get<double>();
  }

 private:
  /// Mean solid fraction of each layer of the whole grid (this rank's cells summed into the layers
  /// of its box, then over the ranks).
  std::vector<double> layerSolidFraction(const fluid::Solver& f) const {
    const CartesianGrid& g = f.grid();
    const CartesianGrid& whole = f.globalGrid();
    const int offset = f.decomposition().distributed() ? f.decomposition().cellOffset()[axis_] : 0;
    const Field& eps = f.couplingFields().voidFraction;
    const int a = axis_, b = (axis_ + 1) % 3, c = (axis_ + 2) % 3;
    std::vector<double> phi(whole.cells[a], 0.0);
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
      phi[static_cast<std::size_t>(offset + l)] = sum;
    }
    if (f.decomposition().distributed()) phi = parallel::sumOverRanks(phi);
    for (double& v : phi) v /= double(whole.cells[b]) * whole.cells[c];
    return phi;
  }
  std::vector<double> smoothed(const std::vector<double>& phi) const {
    const int n = static_cast<int>(phi.size()), half = smoothing_ / 2;
    std::vector<double> out(n);
    for (int l = 0; l < n; ++l) {
      const int lo = std::max(0, l - half), hi = std::min(n - 1, l + half);
      double sum = 0.0;
      for (int m = lo; m <= hi; ++m) sum += phi[m];
      out[l] = sum / (hi - lo + 1);
    }
    return out;
  }
  void initialise(const std::vector<double>& phi, const RunState& s) {
    phiInit_ = phi;
    const double densest = *std::max_element(phi.begin(), phi.end());
    double sum = 0.0;
    int count = 0;
    topLayer_ = 0;
    bottomLayer_ = static_cast<int>(phi.size());
    for (int l = 0; l < static_cast<int>(phi.size()); ++l)
      if (phi[l] > 0.5 * densest) {
        sum += phi[l];
        ++count;
        topLayer_ = l;
        bottomLayer_ = std::min(bottomLayer_, l);
      }
    phi0_ = count > 0 ? sum / count : 0.0;
    const dem::ParticleSet& p = monitoredParticles(s);
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
  int axis_ = 2;
  double threshold_ = 0.1, fitStart_ = 0.2, fitEnd_ = 1e30;
  int smoothing_ = 3;
  std::vector<double> phiInit_;
  bool initialised_ = false;
  double phi0_ = 0.0, atwood_ = 0.0, gravity_ = 9.81;
  int topLayer_ = 0, bottomLayer_ = 0;  // the initial suspension's layers
  LinearFit width_, bubble_, spike_;  // fits of h, upper front and -(lower front) against A g t^2
};

}  // namespace
}  // namespace gf::coupling

GF_REGISTER_MODEL(gf::Monitor, gf::coupling::MixingLayerMonitor, "mixing_layer",
                  "Rayleigh-Taylor mixing-layer width of a suspension layer above clear fluid, and the growth "
                  "coefficient alpha of h = alpha A g t^2 (seed 001 eq. 42)")
