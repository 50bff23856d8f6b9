// Rate-based insertion through a rectangular face: a prescribed mass flow rate enters with a
// prescribed velocity. Particles are placed at random points of the face, avoiding overlaps;
// mass that cannot be placed in a step is carried to the next.
#include <algorithm>
#include <cmath>

#include "dem/insertion/inserter.hpp"

namespace gf::dem {
namespace {
class RateInsertion final : public Inserter {
 public:
  explicit RateInsertion(Params& p) : common_(p) {
    corner_ = p.vec3({"corner", "m", "rate: one corner of the rectangular face"}, {});
    edgeA_ = p.vec3({"edge_a", "m", "rate: first edge vector of the face"}, {1, 0, 0});
    edgeB_ = p.vec3({"edge_b", "m", "rate: second edge vector of the face"}, {0, 1, 0});
    massRate_ = p.real({"mass_flow_rate", "kg/s", "rate: inserted mass per time", Range::positive()}, 0.01);
    start_ = p.real({"start", "s", "rate: time insertion begins", Range::nonNegative()}, 0.0);
    end_ = p.real({"end", "s", "rate: time insertion ends", Range::nonNegative()}, 1e300);
    if (!p.documenting() && norm(cross(edgeA_, edgeB_)) == 0.0) p.fail("edge_b", "parallel to edge_a", "two edges spanning a face");
    nextDiameter_ = common_.size->sample(common_.rng);
  }
  std::size_t insert(InsertionContext& ctx, double time, double dt) override {
    const double t0 = std::max(time, start_), t1 = std::min(time + dt, end_);
    if (t1 <= t0) return 0;
    pendingMass_ += massRate_ * (t1 - t0);
    std::size_t added = 0;
    const double rMax = 0.5 * common_.size->maxDiameter();
    const Vec3 n = normalized(cross(edgeA_, edgeB_));
    OverlapGrid* grid = nullptr;
    OverlapGrid local(2.0 * rMax);
    while (true) {
      const double r = 0.5 * nextDiameter_;
      const double m = common_.density * 4.0 / 3.0 * 3.141592653589793 * r * r * r;
      if (pendingMass_ < m) break;
      if (!grid) {  // particles near the face only
        ctx.addExisting([&](const Vec3& x) { return std::abs(dot(x - corner_, n)) < 3.0 * rMax; }, local);
        grid = &local;
      }
      bool placed = false;
      for (int attempt = 0; attempt < 20 && !placed; ++attempt) {
        const double u = common_.rng.uniform(), v = common_.rng.uniform();
        const Vec3 x = corner_ + u * edgeA_ + v * edgeB_;
        if (grid->overlaps(x, r)) continue;
        grid->add(x, r);
        ctx.particles.add(ctx.nextId++, common_.material, r, common_.density, x, common_.velocity);
        placed = true;
      }
      if (!placed) break;  // face full this step: keep the mass for later
      pendingMass_ -= m;
      ++added;
      nextDiameter_ = common_.size->sample(common_.rng);
    }
    return added;
  }
  SmallestInserted smallest() const override { return common_.smallest(); }
  void save(BinaryWriter& out) const override {
    out.put(pendingMass_);
    out.put(nextDiameter_);
    out.put(common_.rng.state());
  }
  void load(BinaryReader& in) override {
    pendingMass_ = in.get<double>();
    nextDiameter_ = in.get<double>();
    common_.rng.setState(in.get<std::uint64_t>());
  }

  double coarseGraining() const override { return common_.coarseGraining; }
  int material() const override { return common_.material; }

 private:
  InsertionCommon common_;
  Vec3 corner_, edgeA_, edgeB_;
  double massRate_ = 0.0, start_ = 0.0, end_ = 0.0;
  double pendingMass_ = 0.0, nextDiameter_ = 0.0;
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Inserter, gf::dem::RateInsertion, "rate",
                  "mass flow rate through a rectangular face (corner, edge_a, edge_b, mass_flow_rate, velocity)")
