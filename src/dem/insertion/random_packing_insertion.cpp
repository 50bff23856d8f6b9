// Random sequential addition of non-overlapping spheres into a box region, up to a count or a
// solid volume fraction (random sequential addition jams near 0.38, Widom 1966; use it for
// loose initial fillings and let gravity pack them).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem/insertion/inserter.hpp"

namespace gf::dem {
namespace {
class RandomPackingInsertion final : public Inserter {
 public:
  explicit RandomPackingInsertion(Params& p) : common_(p) {
    min_ = p.vec3({"min", "m", "random_packing: lower corner of the region"}, {});
    max_ = p.vec3({"max", "m", "random_packing: upper corner of the region"}, {1, 1, 1});
    count_ = p.integer({"count", "-", "random_packing: number of particles (0: use volume_fraction)",
                        Range::atLeast(0)},
                       0);
    fraction_ = p.real({"volume_fraction", "-", "random_packing: solid volume fraction of the region",
                        Range{0.0, 0.45, true, true}},
                       0.0);
    attempts_ = p.integer({"max_attempts", "-", "random_packing: placement attempts per particle",
                           Range::atLeast(1)},
                          1000);
    if (!p.documenting() && count_ == 0 && fraction_ == 0.0)
      p.fail("count", "neither count nor volume_fraction", "count > 0 or volume_fraction > 0");
    params_ = p;
  }
  std::size_t insert(InsertionContext& ctx, double, double) override {
    if (done_) return 0;
    done_ = true;
    const double dMax = common_.size->maxDiameter();
    OverlapGrid grid(dMax);
    for (std::size_t i = 0; i < ctx.particles.size(); ++i) grid.add(ctx.particles.position[i], ctx.particles.radius[i]);
    // Draw the diameters first (largest placed first), then place them.
    const double regionVolume = (max_.x - min_.x) * (max_.y - min_.y) * (max_.z - min_.z);
    std::vector<double> diameters;
    double solid = 0.0;
    while (count_ > 0 ? static_cast<long long>(diameters.size()) < count_ : solid < fraction_ * regionVolume) {
      const double d = common_.size->sample(common_.rng);
      diameters.push_back(d);
      solid += std::numbers::pi / 6.0 * d * d * d;
    }
    std::stable_sort(diameters.begin(), diameters.end(), std::greater<>());
    std::size_t added = 0;
    for (double d : diameters) {
      const double r = 0.5 * d;
      bool placed = false;
      for (long long a = 0; a < attempts_ && !placed; ++a) {
        Vec3 x;
        for (int c = 0; c < 3; ++c) x[c] = common_.rng.uniform(min_[c] + r, max_[c] - r);
        if (grid.overlaps(x, r)) continue;
        grid.add(x, r);
        ctx.particles.add(ctx.nextId++, common_.material, r, common_.density, x, common_.velocity);
        placed = true;
      }
      if (!placed)
        params_.fail(count_ > 0 ? "count" : "volume_fraction",
                     fmt::format("only {} of {} particles placed", added, diameters.size()),
                     "a larger region or fewer particles (random sequential addition)");
      ++added;
    }
    return added;
  }
  void save(BinaryWriter& out) const override { out.put<std::uint8_t>(done_); }
  void load(BinaryReader& in) override { done_ = in.get<std::uint8_t>() != 0; }

 private:
  InsertionCommon common_;
  Vec3 min_, max_;
  long long count_ = 0, attempts_ = 1000;
  double fraction_ = 0.0;
  bool done_ = false;
  Params params_ = Params::documentation();
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Inserter, gf::dem::RandomPackingInsertion, "random_packing",
                  "random non-overlapping spheres in a box region up to a count or volume fraction")
