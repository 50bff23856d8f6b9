// Random non-overlapping spheres in a box region, up to a count or a solid volume fraction.
// Up to a fraction of 0.25: random sequential addition (RSA; it jams near 0.38, Widom 1966, and
// becomes slow well before). Above: the sites of a hexagonal close-packed lattice (nearest-
// neighbour distance a >= d_max), as loose as the count allows, taken in random order and each
// moved by a random jitter of at most (a - d_max)/2, so no two spheres can overlap. The lattice
// holds up to 0.74 x (d_mean/d_max)^3 in the bulk, less near the region's faces: ~0.65 for
// monodisperse spheres in a region 10 x 10 x 15 d. The fuller, the more crystalline, so let
// gravity or shaking randomise it.
//
// initial_distribution (seed 003 sec. 4.2, Tab. 4.10-4.11: the "kick" that starts the clustering
// of a sedimenting suspension): homogeneous (the default: the region as one), bisected (the
// region cut in two halves normal to split_axis, the lower half holding three times the solid
// concentration of the upper one) or quadrisectioned (cut in four quarters normal to split_axis and
// second_split_axis, the two quarters on one diagonal holding three times the concentration of the
// other two). The mean concentration is the region's either way. The diameters are drawn as
// before and dealt, largest first, to the part whose solid volume lags its share most (3/4 and
// 1/4; 3/8 twice and 1/8 twice), so the 3:1 ratio holds to one particle; each part is then
// filled by random sequential addition (up to a part fraction of 0.25).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem/insertion/inserter.hpp"

namespace gf::dem {
namespace {
/// Above this solid fraction the jittered lattice is used instead of random sequential addition.
constexpr double kRandomSequentialLimit = 0.25;

class RandomPackingInsertion final : public Inserter {
 public:
  explicit RandomPackingInsertion(Params& p) : common_(p) {
    min_ = p.vec3({"min", "m", "random_packing: lower corner of the region"}, {});
    max_ = p.vec3({"max", "m", "random_packing: upper corner of the region"}, {1, 1, 1});
    count_ = p.integer({"count", "-", "random_packing: number of particles (0: use volume_fraction)",
                        Range::atLeast(0)},
                       0);
    fraction_ = p.real({"volume_fraction", "-", "random_packing: solid volume fraction of the region",
                        Range{0.0, 0.74, true, true}},
                       0.0);
    attempts_ = p.integer({"max_attempts", "-", "random_packing: placement attempts per particle",
                           Range::atLeast(1)},
                          1000);
    const std::string layout =
        p.choice({"initial_distribution", "-",
                  "random_packing: homogeneous; bisected = two halves normal to split_axis, the lower with three times "
                  "the solid concentration of the upper; quadrisectioned = four quarters normal to split_axis and "
                  "second_split_axis, two diagonal ones with three times the concentration of the other two (seed 003 "
                  "Tab. 4.10-4.11); the region's mean concentration either way"},
                 {"homogeneous", "bisected", "quadrisectioned"}, "homogeneous");
    parts_ = layout == "homogeneous" ? 1 : layout == "bisected" ? 2 : 4;
    splitAxis_ = p.choice({"split_axis", "-", "random_packing: normal of the cut of bisected and quadrisectioned"},
                          {"x", "y", "z"}, "x")[0] - 'x';
    secondSplitAxis_ =
        p.choice({"second_split_axis", "-", "random_packing: normal of the second cut of quadrisectioned"},
                 {"x", "y", "z"}, "y")[0] - 'x';
    if (!p.documenting() && parts_ == 4 && secondSplitAxis_ == splitAxis_)
      p.fail("second_split_axis", "the same axis as split_axis", "another axis than split_axis");
    if (!p.documenting() && count_ == 0 && fraction_ == 0.0)
      p.fail("count", "neither count nor volume_fraction", "count > 0 or volume_fraction > 0");
    params_ = p;
  }
  std::size_t insert(InsertionContext& ctx, double, double) override {
    if (done_) return 0;
    done_ = true;
    const double dMax = common_.size->maxDiameter();
    OverlapGrid grid(dMax);
    ctx.addExisting([](const Vec3&) { return true; }, grid);
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
    if (parts_ > 1) return insertInParts(ctx, grid, diameters, regionVolume);
    if (solid > kRandomSequentialLimit * regionVolume) return insertOnLattice(ctx, grid, diameters, dMax, solid);
    std::size_t added = 0;
    placeRandomly(ctx, grid, diameters, min_, max_, added, diameters.size());
    return added;
  }
  /// Random sequential addition of spheres of `diameters` in the box [lo, hi] (centres a radius
  /// inside it), each placed where it overlaps none already placed; `added` counts the placed
  /// particles of the `total` asked for (for the message when one cannot be placed).
  void placeRandomly(InsertionContext& ctx, OverlapGrid& grid, const std::vector<double>& diameters, const Vec3& lo,
                     const Vec3& hi, std::size_t& added, std::size_t total) {
    for (double d : diameters) {
      const double r = 0.5 * d;
      bool placed = false;
      for (long long a = 0; a < attempts_ && !placed; ++a) {
        Vec3 x;
        for (int c = 0; c < 3; ++c) x[c] = common_.rng.uniform(lo[c] + r, hi[c] - r);
        if (grid.overlaps(x, r)) continue;
        grid.add(x, r);
        ctx.particles.add(ctx.nextId++, common_.material, r, common_.density, x, common_.velocity);
        placed = true;
      }
      if (!placed)
        params_.fail(count_ > 0 ? "count" : "volume_fraction", fmt::format("only {} of {} particles placed", added, total),
                     "a larger region or fewer particles (random sequential addition)");
      ++added;
    }
  }
  /// bisected / quadrisectioned (see the file comment).
  std::size_t insertInParts(InsertionContext& ctx, OverlapGrid& grid, const std::vector<double>& diameters,
                            double regionVolume) {
    // part q: its box and its share of the solid volume (dense parts three times the sparse ones)
    std::vector<Vec3> lo(static_cast<std::size_t>(parts_), min_), hi(static_cast<std::size_t>(parts_), max_);
    std::vector<double> share(static_cast<std::size_t>(parts_));
    const double midA = 0.5 * (min_[splitAxis_] + max_[splitAxis_]);
    const double midB = 0.5 * (min_[secondSplitAxis_] + max_[secondSplitAxis_]);
    for (int q = 0; q < parts_; ++q) {
      const int a = q & 1, b = q >> 1;  // lower (0) or upper (1) side of each cut
      (a ? lo : hi)[q][splitAxis_] = midA;
      if (parts_ == 4) (b ? lo : hi)[q][secondSplitAxis_] = midB;
      const bool dense = parts_ == 2 ? a == 0 : a == b;
      share[q] = (dense ? 3.0 : 1.0) / (parts_ == 2 ? 4.0 : 8.0);
    }
    std::vector<double> solid(static_cast<std::size_t>(parts_), 0.0);
    std::vector<std::vector<double>> dealt(static_cast<std::size_t>(parts_));
    double total = 0.0;
    for (double d : diameters) total += std::numbers::pi / 6.0 * d * d * d;
    for (double d : diameters) {
      int best = 0;  // the part furthest below its share
      for (int q = 1; q < parts_; ++q)
        if (solid[q] - share[q] * total < solid[best] - share[best] * total) best = q;
      dealt[best].push_back(d);
      solid[best] += std::numbers::pi / 6.0 * d * d * d;
    }
    std::size_t added = 0;
    for (int q = 0; q < parts_; ++q) {
      const double partVolume = regionVolume / parts_;
      if (solid[q] > kRandomSequentialLimit * partVolume)
        params_.fail("initial_distribution",
                     fmt::format("a part with solid fraction {:.3f}", solid[q] / partVolume),
                     "at most 0.25 in each part (random sequential addition): a lower volume_fraction or count");
      placeRandomly(ctx, grid, dealt[q], lo[q], hi[q], added, diameters.size());
    }
    return added;
  }

  /// Jittered close-packed lattice (see the file comment).
  std::size_t insertOnLattice(InsertionContext& ctx, OverlapGrid& grid, const std::vector<double>& diameters,
                              double dMax, double solid) {
    const std::size_t n = diameters.size();
    const Vec3 size = max_ - min_;
    // Loosest nearest-neighbour distance with enough sites: start from the one that gives n sites
    // in the region's volume and shrink until the sites inside (shrunk by r_max + jitter) suffice.
    // (close packing has sqrt(2)/a^3 sites per m^3; the last try is a = d_max (1 + 1e-6), so that
    // round-off cannot make touching neighbours overlap).
    const double closest = dMax * (1.0 + 1e-6);
    double spacing = std::max(closest, std::cbrt(std::sqrt(2.0) * size.x * size.y * size.z / static_cast<double>(n)));
    std::vector<Vec3> sites;
    for (;; spacing = std::max(closest, 0.995 * spacing)) {
      const double jitter = 0.5 * (spacing - dMax);
      const Vec3 lo = min_ + Vec3{1, 1, 1} * (0.5 * dMax + jitter), hi = max_ - Vec3{1, 1, 1} * (0.5 * dMax + jitter);
      sites = closePackedSites(lo, hi, spacing);
      if (sites.size() >= n || spacing == closest) break;
    }
    if (sites.size() < n)
      params_.fail(count_ > 0 ? "count" : "volume_fraction",
                   fmt::format("{} particles (solid fraction {:.3f}); a lattice of d_max = {} m holds {}", n,
                               solid / (size.x * size.y * size.z), dMax, sites.size()),
                   "a larger region or fewer particles (random_packing fills up to ~0.65, see docs/dem.md)");
    const double jitter = 0.5 * (spacing - dMax) / std::sqrt(3.0);  // per axis: |displacement| <= (a - d_max)/2
    std::size_t added = 0, next = 0;
    for (double d : diameters) {
      bool placed = false;
      while (!placed && next < sites.size()) {
        // Partial Fisher-Yates shuffle: site `next` is drawn from the ones not used yet.
        const std::size_t pick = next + static_cast<std::size_t>(common_.rng.uniform() * (sites.size() - next));
        std::swap(sites[next], sites[std::min(pick, sites.size() - 1)]);
        Vec3 x = sites[next++];
        for (int c = 0; c < 3; ++c) x[c] += common_.rng.uniform(-jitter, jitter);
        if (grid.overlaps(x, 0.5 * d)) continue;  // particles present before this insertion
        ctx.particles.add(ctx.nextId++, common_.material, 0.5 * d, common_.density, x, common_.velocity);
        placed = true;
      }
      if (!placed)
        params_.fail(count_ > 0 ? "count" : "volume_fraction",
                     fmt::format("only {} of {} particles placed (the region holds other particles)", added, n),
                     "a larger region or fewer particles");
      ++added;
    }
    return added;
  }

  /// Sites of a hexagonal close-packed lattice (AB-stacked triangular layers normal to z) with
  /// nearest-neighbour distance `spacing` inside [lo, hi]; its close-packed layers are aligned
  /// with the region's faces, so a box region holds more of them than of a cubic-cell FCC.
  static std::vector<Vec3> closePackedSites(const Vec3& lo, const Vec3& top, double spacing) {
    std::vector<Vec3> sites;
    const double rowPitch = spacing * std::sqrt(3.0) / 2.0, layerPitch = spacing * std::sqrt(2.0 / 3.0);
    const Vec3 hi = top + Vec3{1, 1, 1} * (1e-9 * spacing);  // a site exactly on the face counts
    for (int k = 0; lo.z + k * layerPitch <= hi.z; ++k) {
      const double layerX = (k % 2) * 0.5 * spacing, layerY = (k % 2) * spacing * std::sqrt(3.0) / 6.0;
      for (int j = 0; lo.y + layerY + j * rowPitch <= hi.y; ++j) {
        const double rowX = layerX + (j % 2) * 0.5 * spacing;
        for (int i = 0; lo.x + rowX + i * spacing <= hi.x; ++i)
          sites.push_back({lo.x + rowX + i * spacing, lo.y + layerY + j * rowPitch, lo.z + k * layerPitch});
      }
    }
    return sites;
  }

  SmallestInserted smallest() const override { return common_.smallest(); }
  void save(BinaryWriter& out) const override { out.put<std::uint8_t>(done_); }
  void load(BinaryReader& in) override { done_ = in.get<std::uint8_t>() != 0; }

  double coarseGraining() const override { return common_.coarseGraining; }
  int material() const override { return common_.material; }

 private:
  InsertionCommon common_;
  Vec3 min_, max_;
  long long count_ = 0, attempts_ = 1000;
  double fraction_ = 0.0;
  int parts_ = 1, splitAxis_ = 0, secondSplitAxis_ = 1;  // initial_distribution
  bool done_ = false;
  Params params_ = Params::documentation();
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Inserter, gf::dem::RandomPackingInsertion, "random_packing",
                  "random non-overlapping spheres in a box region up to a count or volume fraction")
