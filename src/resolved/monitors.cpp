// Monitor 'resolved_body_forces': hydrodynamic force and torque on one resolved body (a fixed body
// of resolved.bodies, or a particle by id), its drag and lift coefficients
//   Cd = 2 F_flow / (rho U^2 A),  Cl = 2 F_lift / (rho U^2 A)
// (A = pi R^2 for a sphere, 2 R x domain depth for a cylinder along z, resolved.bodies[].reference_area
// if set; an stl body: R of the sphere of its volume), and the Strouhal number St = f D / U (D = 2 R)
// from the lift signal: f from the upward zero crossings of Cl (linear between samples),
// over the last up to four periods; a crossing counts once Cl has been below -lift_threshold since
// the previous one (the noise of a steady, symmetric wake does not count). St is 0 until two
// crossings were seen. Sample every coupling step (interval: 0) or at least 20 times per period.
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>

#include "core/monitor.hpp"
#include "dem/system.hpp"
#include "resolved/fictitious_domain.hpp"

namespace gf::resolved {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int axisOf(const std::string& a) { return a == "x" ? 0 : (a == "y" ? 1 : 2); }

class BodyForcesMonitor : public Monitor {
 public:
  explicit BodyForcesMonitor(Params& p)
      : body_(p.integer({"body", "-", "index of the body in resolved.bodies (from 0); ignored when particle_id is set",
                         Range::nonNegative()},
                        0)),
        particle_(p.integer({"particle_id", "-", "id of a resolved particle instead of a fixed body; -1: none",
                             Range::atLeast(-1)},
                            -1)),
        velocity_(p.real({"reference_velocity", "m/s", "velocity U of the coefficients", Range::positive()}, 1.0)),
        flow_(axisOf(p.choice({"flow_axis", "-", "axis of the drag (the mean flow)"}, {"x", "y", "z"}, "x"))),
        lift_(axisOf(p.choice({"lift_axis", "-", "axis of the lift"}, {"x", "y", "z"}, "y"))),
        threshold_(p.real({"lift_threshold", "-", "Cl below -this arms the next upward crossing (Strouhal number)",
                           Range::nonNegative()},
                          0.01)) {}

  std::vector<MonitorColumn> columns() const override {
    return {{"fx", "N"},  {"fy", "N"},   {"fz", "N"},  {"tx", "N m"}, {"ty", "N m"},
            {"tz", "N m"}, {"cd", "-"}, {"cl", "-"}, {"strouhal", "-"}};
  }

  std::vector<double> sample(const RunState& st) override {
    if (!st.resolved) return std::vector<double>(9, kNaN);
    const FictitiousDomain& fd = *st.resolved;
    BodyLoad load;
    double radius = 0.0, area = 0.0;
    if (particle_ >= 0) {
      const dem::ParticleSet& p = monitoredParticles(st);
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.id[i] == particle_) {
          radius = p.radius[i];
          if (p.hasExternalForces) load = {p.externalForce[i], p.externalTorque[i]};
        }
      if (radius == 0.0) return std::vector<double>(9, kNaN);
      area = std::numbers::pi * radius * radius;
    } else {
      if (body_ >= static_cast<long long>(fd.fixedBodies().size())) return std::vector<double>(9, kNaN);
      const FixedBody& b = fd.fixedBodies()[static_cast<std::size_t>(body_)];
      load = b.load;
      radius = b.body.radius;
      area = b.referenceArea;
    }
    const double q = 0.5 * fd.fluidDensity() * velocity_ * velocity_ * area;
    const double cd = load.force[flow_] / q, cl = load.force[lift_] / q;
    // Strouhal number from the upward zero crossings of Cl.
    if (cl < -threshold_) armed_ = true;
    if (armed_ && hasPrevious_ && previousCl_ < 0.0 && cl >= 0.0) {
      const double t = previousTime_ + (st.time - previousTime_) * (-previousCl_) / (cl - previousCl_);
      crossings_.push_back(t);
      if (crossings_.size() > 5) crossings_.pop_front();
      armed_ = false;
    }
    previousCl_ = cl;
    previousTime_ = st.time;
    hasPrevious_ = true;
    double strouhal = 0.0;
    if (crossings_.size() >= 2) {
      const double period = (crossings_.back() - crossings_.front()) / static_cast<double>(crossings_.size() - 1);
      if (period > 0.0) strouhal = 2.0 * radius / (period * velocity_);
    }
    return {load.force.x, load.force.y, load.force.z, load.torque.x, load.torque.y, load.torque.z, cd, cl, strouhal};
  }

  void save(BinaryWriter& out) const override {
    out.put<std::uint8_t>(armed_ ? 1 : 0);
    out.put<std::uint8_t>(hasPrevious_ ? 1 : 0);
    out.put(previousCl_);
    out.put(previousTime_);
    out.putVector(std::vector<double>(crossings_.begin(), crossings_.end()));
  }
  void load(BinaryReader& in) override {
    armed_ = in.get<std::uint8_t>() != 0;
    hasPrevious_ = in.get<std::uint8_t>() != 0;
    previousCl_ = in.get<double>();
    previousTime_ = in.get<double>();
    const auto c = in.getVector<double>();
    crossings_.assign(c.begin(), c.end());
  }

 private:
  long long body_;
  long long particle_;
  double velocity_;
  int flow_, lift_;
  double threshold_;
  bool armed_ = false, hasPrevious_ = false;
  double previousCl_ = 0.0, previousTime_ = 0.0;
  std::deque<double> crossings_;
};

}  // namespace
}  // namespace gf::resolved

GF_REGISTER_MODEL(gf::Monitor, gf::resolved::BodyForcesMonitor, "resolved_body_forces",
                  "force, torque, Cd, Cl and Strouhal number (from the lift) of one resolved body: a fixed body of "
                  "resolved.bodies or a particle")
