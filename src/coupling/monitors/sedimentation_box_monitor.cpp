// Monitor "sedimentation_box": the post-processing of seed 003's periodic-box sedimentation
// (sec. 4.1.3, lines 1107-1111) for a fully periodic suspension whose fluid is held at zero net
// volume flux (fluid.driving mode flow_rate, bulk_velocity 0, along the gravity axis: the mean
// pressure gradient found then carries the mixture's weight). Columns:
//   slip                 domain-averaged slip along gravity, seed 003 eq. 3.6:
//                        <u_slip> = <sum phi_i v_i>/<phi_p> - <u (1 - phi_p)>/<1 - phi_p>, i.e. the
//                        volume-weighted mean particle velocity minus the Favre-averaged fluid
//                        velocity, projected on g/|g| (positive: particles fall through the gas), m/s
//   terminal_velocity    u_t of the reference particle: Stokes, eq. 3.4, at the Sauter mean primary
//                        diameter (eq. 3.5) and the particles' mean density (or the key), m/s
//   slip_over_ut         <u_slip> / u_t
//   slip_over_ut_mean    its mean over the samples from average_start on (the seed averages over the
//                        last 90 % of the run: average_start = 0.1 x time.end), 0 before
//   slip_over_ut_class_i per size class of class_diameters (primary diameters; each particle counts
//                        in the nearest): the class's volume-weighted mean velocity minus the same
//                        Favre fluid velocity, over u_t
//   momentum_error       domain-averaged dimensionless momentum error (sec. 4.1.3): the integral
//                        momentum sum m_p v_p + sum rho_f eps u V_cell along g over the reference
//                        momentum (particle mass x <u_slip>)
//   max_overlap_over_radius  largest particle-particle overlap / smaller radius (the seed's
//                        "maximum overlap", 1 - min distance / smallest diameter, is half of it
//                        for equal spheres)
//   parcels, primary_particles  the particles and the primary particles they stand for
//                        (sum alpha^3, alpha of each particle's insertion)
//   solid_fraction       <phi_p> = sum V_p / domain volume
//   driving_pressure_gradient  the fluid's mean driving -dp/dx_axis (Pa/m); with flow_rate
//                        control along the gravity axis its magnitude tends to the mixture weight
//   mixture_weight       (rho_f (1 - <phi_p>) + rho_p <phi_p>) |g|, Pa/m
// Particle sums run over monitoredParticles (gathered on rank 0 under MPI); the fluid sums are
// reduced over the ranks (fluid::sumOverRanks) and the contact statistics are collective.
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "core/monitor.hpp"
#include "coupling/coupler.hpp"
#include "dem/system.hpp"
#include "fluid/sampling.hpp"
#include "fluid/solver.hpp"

namespace gf::coupling {
namespace {

class SedimentationBoxMonitor final : public Monitor {
 public:
  explicit SedimentationBoxMonitor(Params& p) {
    terminalVelocity_ = p.real({"terminal_velocity", "m/s",
                                "sedimentation_box: u_t of the normalisation; 0 = Stokes (seed 003 eq. 3.4) at the "
                                "Sauter mean primary diameter and mean density of the particles",
                                Range::nonNegative()},
                               0.0);
    classDiameters_ = p.reals({"class_diameters", "m",
                               "sedimentation_box: primary diameters of the size classes reported one by one (each "
                               "particle counts in the nearest); empty: the overall slip only"},
                              {});
    averageStart_ = p.real({"average_start", "s",
                            "sedimentation_box: start of the mean of slip_over_ut (seed 003: the last 90 % of the "
                            "run, i.e. 0.1 x time.end)",
                            Range::nonNegative()},
                           0.0);
  }
  std::vector<MonitorColumn> columns() const override {
    std::vector<MonitorColumn> c = {{"slip", "m/s"}, {"terminal_velocity", "m/s"}, {"slip_over_ut", "-"},
                                    {"slip_over_ut_mean", "-"}};
    for (std::size_t i = 0; i < classDiameters_.size(); ++i) c.push_back({fmt::format("slip_over_ut_class_{}", i), "-"});
    for (const MonitorColumn& m : std::vector<MonitorColumn>{{"momentum_error", "-"},
                                                             {"max_overlap_over_radius", "-"},
                                                             {"parcels", "-"},
                                                             {"primary_particles", "-"},
                                                             {"solid_fraction", "-"},
                                                             {"driving_pressure_gradient", "Pa/m"},
                                                             {"mixture_weight", "Pa/m"}})
      c.push_back(m);
    return c;
  }
  std::vector<double> sample(const RunState& s) override {
    std::vector<double> row(columns().size(), 0.0);
    if (!s.dem || !s.fluid || !s.coupling) return row;
    const double g = norm(s.gravity);
    const Vec3 down = g > 0.0 ? (1.0 / g) * s.gravity : Vec3{0.0, 0.0, -1.0};
    // fluid: sum eps, sum eps u (cell-centred: mean of the two faces), collective
    const fluid::Solver& f = *s.fluid;
    const CartesianGrid& grid = f.grid();
    const Field& eps = f.couplingFields().voidFraction;
    double epsSum = 0.0, epsU = 0.0;
    for (int k = 0; k < grid.cells[2]; ++k)
      for (int j = 0; j < grid.cells[1]; ++j)
        for (int i = 0; i < grid.cells[0]; ++i) {
          const Vec3 u{0.5 * (f.velocity(0)(i, j, k) + f.velocity(0)(i + 1, j, k)),
                       0.5 * (f.velocity(1)(i, j, k) + f.velocity(1)(i, j + 1, k)),
                       0.5 * (f.velocity(2)(i, j, k) + f.velocity(2)(i, j, k + 1))};
          epsSum += eps(i, j, k);
          epsU += eps(i, j, k) * dot(u, down);
        }
    std::tie(epsSum, epsU) = fluid::sumOverRanks(f, std::pair<double, double>{epsSum, epsU});
    const double cellCount = epsSum > 0.0 ? fluid::sumOverRanks(f, static_cast<double>(grid.interiorCellCount())) : 0.0;
    const double fluidVelocity = epsSum > 0.0 ? epsU / epsSum : 0.0;  // Favre mean along g
    const double fluidMomentum = f.density() * epsU * grid.cellVolume();
    const double maxOverlap = s.dem->contactStatistics().maxOverlapRatio;  // (collective)
    const double drive = f.drivingPressureGradient();
    // particles
    const dem::ParticleSet& p = monitoredParticles(s);
    const CoarseGraining& cg = s.coupling->settings().coarseGraining;
    const std::size_t nc = classDiameters_.size();
    std::vector<double> classVolume(nc, 0.0), classVolumeVelocity(nc, 0.0);
    double volume = 0.0, volumeVelocity = 0.0, volumeOverDiameter = 0.0, mass = 0.0, momentum = 0.0, primaries = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double d = 2.0 * p.radius[i];
      const double v = std::numbers::pi / 6.0 * d * d * d;
      const double alpha = cg.factorOf(p.type[i]);
      const double along = dot(p.velocity[i], down);
      volume += v;
      volumeVelocity += v * along;
      volumeOverDiameter += v / (d / alpha);
      mass += p.mass[i];
      momentum += p.mass[i] * along;
      primaries += alpha * alpha * alpha;
      if (nc > 0) {
        std::size_t best = 0;
        for (std::size_t c = 1; c < nc; ++c)
          if (std::abs(classDiameters_[c] - d / alpha) < std::abs(classDiameters_[best] - d / alpha)) best = c;
        classVolume[best] += v;
        classVolumeVelocity[best] += v * along;
      }
    }
    if (!(volume > 0.0)) return row;
    const double slip = volumeVelocity / volume - fluidVelocity;
    const double rhoP = mass / volume, d32 = volume / volumeOverDiameter, mu = f.viscosity(), rhoF = f.density();
    // Stokes terminal velocity, seed 003 eq. 3.4: u_t = d^2 (rho_p - rho_f) g / (18 mu)
    const double ut = terminalVelocity_ > 0.0 ? terminalVelocity_ : d32 * d32 * (rhoP - rhoF) * g / (18.0 * mu);
    const double ratio = ut > 0.0 ? slip / ut : 0.0;
    if (s.time + 1e-12 >= averageStart_) {
      averageSum_ += ratio;
      averageCount_ += 1.0;
    }
    const double phi = cellCount > 0.0 ? volume / (cellCount * grid.cellVolume()) : 0.0;
    std::size_t c = 0;
    row[c++] = slip;
    row[c++] = ut;
    row[c++] = ratio;
    row[c++] = averageCount_ > 0.0 ? averageSum_ / averageCount_ : 0.0;
    for (std::size_t i = 0; i < nc; ++i)
      row[c++] = classVolume[i] > 0.0 && ut > 0.0 ? (classVolumeVelocity[i] / classVolume[i] - fluidVelocity) / ut : 0.0;
    row[c++] = slip != 0.0 ? (momentum + fluidMomentum) / (mass * slip) : 0.0;
    row[c++] = maxOverlap;
    row[c++] = static_cast<double>(p.size());
    row[c++] = primaries;
    row[c++] = phi;
    row[c++] = drive;
    row[c++] = (rhoF * (1.0 - phi) + rhoP * phi) * g;
    return row;
  }
  void save(BinaryWriter& out) const override {
    out.put(averageSum_);
    out.put(averageCount_);
  }
  void load(BinaryReader& in) override {
    averageSum_ = in.get<double>();
    averageCount_ = in.get<double>();
  }

 private:
  double terminalVelocity_ = 0.0, averageStart_ = 0.0;
  std::vector<double> classDiameters_;
  double averageSum_ = 0.0, averageCount_ = 0.0;
};

}  // namespace
}  // namespace gf::coupling

GF_REGISTER_MODEL(gf::Monitor, gf::coupling::SedimentationBoxMonitor, "sedimentation_box",
                  "periodic-box sedimentation (seed 003 sec. 4.1.3): domain-averaged slip over u_t overall and per "
                  "size class, its mean, momentum error, maximum overlap, parcel and primary particle counts")
