// Monitor 'resolved_particle_pair': two settling particles and the phases of drafting, kissing and
// tumbling (seed 000 lines 799-806; Fortes, Joseph & Lundgren 1987, J. Fluid Mech. 177, 467;
// Glowinski et al. 2001, J. Comput. Phys. 169, 363). "Up" is against gravity. The trailing particle
// is the one higher at the first sample, the leading one the lower.
//   gap            surface gap |x_b - x_a| - r_a - r_b over the mean diameter d
//   separation     height of the trailing particle above the leading one, over d
//   lateral        distance of the centres across gravity, over d
//   approach       the trailing particle's downward velocity less the leading one's, m/s
//   drafting_time  first time the trailing particle falls faster than the leading one by more than
//                  approach_fraction of the leading one's speed, with the gap closed by 10 % of its
//                  initial value (it gains on it in the leading one's wake)
//   contact_time   first time the gap is below kissing_gap (in d), linear between samples (kissing)
//   tumbling_time  first time after contact that the trailing particle is no more than
//                  tumbling_separation d above the leading one (the pair has turned over to side by
//                  side, or the vertical order reverses), linear between samples
//   phases_in_order 1 once drafting, contact and tumbling were seen in that order, else 0
// The times are -1 until their phase is seen. Sample every coupling step or often enough to catch
// the contact (interval: 0).
#include <cmath>
#include <limits>

#include "core/monitor.hpp"
#include "dem/system.hpp"
#include "resolved/fictitious_domain.hpp"

namespace gf::resolved {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class ParticlePairMonitor : public Monitor {
 public:
  explicit ParticlePairMonitor(Params& p)
      : a_(p.integer({"particle_id", "-", "id of the first particle of the pair", Range::nonNegative()}, 0)),
        b_(p.integer({"other_id", "-", "id of the second particle of the pair", Range::nonNegative()}, 1)),
        kissingGap_(p.real({"kissing_gap", "-",
                            "surface gap over the mean diameter below which the pair is in contact (kissing)",
                            Range::nonNegative()},
                           0.05)),
        approachFraction_(p.real({"approach_fraction", "-",
                                  "drafting: the trailing particle falls faster than the leading one by more "
                                  "than this fraction of the leading one's speed",
                                  Range::nonNegative()},
                                 0.05)),
        tumblingSeparation_(p.real({"tumbling_separation", "-",
                                    "tumbling: after contact, the trailing particle's height above the leading one "
                                    "falls below this many mean diameters (side by side, or below it)"},
                                   0.1)) {}

  std::vector<MonitorColumn> columns() const override {
    return {{"gap", "-"},          {"separation", "-"},   {"lateral", "-"},       {"approach", "m/s"},
            {"drafting_time", "s"}, {"contact_time", "s"}, {"tumbling_time", "s"}, {"phases_in_order", "-"}};
  }

  std::vector<double> sample(const RunState& st) override {
    const dem::ParticleSet& p = monitoredParticles(st);
    std::size_t ia = p.size(), ib = p.size();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.isGhost(i)) continue;
      if (p.id[i] == a_) ia = i;
      if (p.id[i] == b_) ib = i;
    }
    if (ia == p.size() || ib == p.size()) return std::vector<double>(8, kNaN);
    const double gNorm = norm(st.gravity);
    const Vec3 up = gNorm > 0.0 ? -1.0 / gNorm * st.gravity : Vec3{0.0, 0.0, 1.0};
    if (!started_) {  // the trailing particle: the higher one
      trailingIsB_ = dot(p.position[ib] - p.position[ia], up) >= 0.0;
    }
    const std::size_t lead = trailingIsB_ ? ia : ib, trail = trailingIsB_ ? ib : ia;
    const double d = p.radius[lead] + p.radius[trail];
    const Vec3 r = p.position[trail] - p.position[lead];
    const double gap = (norm(r) - d) / d;
    const double separation = dot(r, up) / d;
    const double lateral = norm(r - dot(r, up) * up) / d;
    const double fallLead = -dot(p.velocity[lead], up), fallTrail = -dot(p.velocity[trail], up);
    const double approach = fallTrail - fallLead;
    if (!started_) {
      initialGap_ = gap;
      started_ = true;
    }
    const double t = st.time;
    if (drafting_ < 0.0 && contact_ < 0.0 && fallLead > 0.0 && approach > approachFraction_ * fallLead &&
        gap < 0.9 * initialGap_)
      drafting_ = t;
    if (contact_ < 0.0 && gap < kissingGap_)
      contact_ = hasPrevious_ && previousGap_ > kissingGap_
                     ? previousTime_ + (t - previousTime_) * (previousGap_ - kissingGap_) / (previousGap_ - gap)
                     : t;
    const double ts = tumblingSeparation_;
    if (contact_ >= 0.0 && tumbling_ < 0.0 && separation < ts)
      tumbling_ = hasPrevious_ && previousSeparation_ > ts
                      ? previousTime_ + (t - previousTime_) * (previousSeparation_ - ts) / (previousSeparation_ - separation)
                      : t;
    previousGap_ = gap;
    previousSeparation_ = separation;
    previousTime_ = t;
    hasPrevious_ = true;
    const bool ordered = drafting_ >= 0.0 && contact_ >= drafting_ && tumbling_ >= contact_;
    return {gap, separation, lateral, approach, drafting_, contact_, tumbling_, ordered ? 1.0 : 0.0};
  }

  void save(BinaryWriter& out) const override {
    out.put<std::uint8_t>(started_ ? 1 : 0);
    out.put<std::uint8_t>(trailingIsB_ ? 1 : 0);
    out.put<std::uint8_t>(hasPrevious_ ? 1 : 0);
    for (double v : {initialGap_, previousGap_, previousSeparation_, previousTime_, drafting_, contact_, tumbling_})
      out.put(v);
  }
  void load(BinaryReader& in) override {
    started_ = in.get<std::uint8_t>() != 0;
    trailingIsB_ = in.get<std::uint8_t>() != 0;
    hasPrevious_ = in.get<std::uint8_t>() != 0;
    for (double* v : {&initialGap_, &previousGap_, &previousSeparation_, &previousTime_, &drafting_, &contact_, &tumbling_})
      *v = in.get<double>();
  }

 private:
  long long a_, b_;
  double kissingGap_, approachFraction_, tumblingSeparation_;
  bool started_ = false, trailingIsB_ = true, hasPrevious_ = false;
  double initialGap_ = 0.0, previousGap_ = 0.0, previousSeparation_ = 0.0, previousTime_ = 0.0;
  double drafting_ = -1.0, contact_ = -1.0, tumbling_ = -1.0;
};

}  // namespace
}  // namespace gf::resolved

GF_REGISTER_MODEL(gf::Monitor, gf::resolved::ParticlePairMonitor, "resolved_particle_pair",
                  "two settling particles: gap, separation, approach velocity and the times of drafting, first "
                  "contact (kissing) and tumbling")
