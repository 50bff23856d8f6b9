#include "dem/wall_contact_list.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "dem/neighbour_list.hpp"

namespace gf::dem {

namespace {

/// Triangles of meshes binned on a uniform grid by their bounding boxes grown by the largest
/// reach (radius + skin): a sphere within reach of a triangle lies in a bin that lists it, so a
/// particle tests the triangles of its bin instead of every triangle (O(n) instead of O(n x
/// triangles) per build). The other primitives (planes, cylinders, cones) are tested by every
/// particle. Every list ascends, so a particle's entries come in primitive order either way.
class TriangleBins {
 public:
  static constexpr std::size_t kMinTriangles = 32;  // fewer: every particle tests every primitive

  /// False (and no bins) if the primitives hold fewer than kMinTriangles triangles. The reach is
  /// the largest radius + skin.
  bool build(const std::vector<WallPrimitive>& primitives, const std::vector<double>& radius, double skin) {
    others_.clear();
    std::vector<std::uint32_t> triangles;
    for (std::uint32_t w = 0; w < primitives.size(); ++w)
      (primitives[w].kind == PrimitiveKind::Triangle ? triangles : others_).push_back(w);
    if (triangles.size() < kMinTriangles) return false;
    double reach = 0.0;
    for (double r : radius) reach = std::max(reach, r);
    reach += skin;
    auto boundsOf = [&](const WallPrimitive& t, Vec3& lo, Vec3& hi) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min({t.a[a], t.b[a], t.c[a]}) - reach;
        hi[a] = std::max({t.a[a], t.b[a], t.c[a]}) + reach;
      }
    };
    Vec3 lo, hi, tlo, thi;
    double meanSize = 0.0;
    boundsOf(primitives[triangles[0]], lo, hi);
    for (std::uint32_t w : triangles) {
      boundsOf(primitives[w], tlo, thi);
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], tlo[a]), hi[a] = std::max(hi[a], thi[a]);
      meanSize += std::max({thi.x - tlo.x, thi.y - tlo.y, thi.z - tlo.z});
    }
    meanSize /= static_cast<double>(triangles.size());
    // Bins about a grown triangle wide, at most a few per triangle.
    double h = meanSize;
    const double maxBins = 4.0 * static_cast<double>(triangles.size()) + 4096.0;
    auto count = [&](int a) { return std::max(1.0, std::ceil((hi[a] - lo[a]) / h)); };
    while (count(0) * count(1) * count(2) > maxBins) h *= 1.26;
    origin_ = lo;
    for (int a = 0; a < 3; ++a) dims_[a] = static_cast<int>(count(a));
    width_ = h;
    upper_ = hi;
    // Two passes (count, fill) in ascending triangle order: each bin's list ascends.
    start_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    std::vector<std::uint32_t> fill;  // next free entry of each bin (fill pass)
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1) {
        for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
        entries_.resize(start_.back());
        fill.assign(start_.begin(), start_.end() - 1);
      }
      for (std::uint32_t w : triangles) {
        boundsOf(primitives[w], tlo, thi);
        int c0[3], c1[3];
        cellOf(tlo, c0);
        cellOf(thi, c1);
        for (int k = c0[2]; k <= c1[2]; ++k)
          for (int j = c0[1]; j <= c1[1]; ++j)
            for (int i = c0[0]; i <= c1[0]; ++i) {
              const std::size_t b = (static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i;
              if (pass == 0) ++start_[b + 1];
              else entries_[fill[b]++] = w;
            }
      }
    }
    return true;
  }

  const std::vector<std::uint32_t>& others() const { return others_; }

  /// The triangles of the bin holding x (none outside the grown bounds of every triangle).
  std::pair<const std::uint32_t*, const std::uint32_t*> trianglesNear(const Vec3& x) const {
    for (int a = 0; a < 3; ++a)
      if (!(x[a] >= origin_[a] && x[a] <= upper_[a])) return {nullptr, nullptr};
    int c[3];
    cellOf(x, c);
    const std::size_t b = (static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
    return {entries_.data() + start_[b], entries_.data() + start_[b + 1]};
  }

 private:
  void cellOf(const Vec3& x, int c[3]) const {
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((x[a] - origin_[a]) / width_)), 0, dims_[a] - 1);
  }
  Vec3 origin_, upper_;
  double width_ = 1.0;
  int dims_[3] = {1, 1, 1};
  std::vector<std::uint32_t> start_, entries_, others_;
};

}  // namespace

void WallContactList::build(const ParticleSet& p, const std::vector<WallPrimitive>& primitives, double skin,
                            const std::vector<std::int64_t>& previousIndex, bool withRollingHistory) {
  const std::size_t n = p.size();
  const std::uint32_t np = static_cast<std::uint32_t>(primitives.size());
  TriangleBins bins;
  const bool binned = bins.build(primitives, p.radius, skin);
  std::vector<std::uint32_t> oldStart = std::move(rowStart);
  std::vector<std::uint32_t> oldPrimitive = std::move(primitive);
  std::vector<Vec3> oldTangential = std::move(tangentialHistory);
  std::vector<Vec3> oldRolling = std::move(rollingHistory);
  const bool carryRolling = withRollingHistory && oldRolling.size() == oldPrimitive.size();
  const std::int64_t oldRows = oldStart.empty() ? 0 : static_cast<std::int64_t>(oldStart.size()) - 1;
  buildCompressedRows(
      n, scratch_, rowStart, primitive,
      [&](std::size_t i, std::vector<std::uint32_t>& out) {
        const Vec3 x = p.position[i];
        const double reach = p.radius[i] + skin;
        auto test = [&](std::uint32_t w) {
          const WallPrimitive& prim = primitives[w];
          // planes inline (the common box and distributor walls), the same value as distanceToPrimitive
          const double d = prim.kind == PrimitiveKind::Plane ? dot(x - prim.a, prim.b) : distanceToPrimitive(prim, x).distance;
          if (d < reach) out.push_back(w);
        };
        if (!binned) {
          for (std::uint32_t w = 0; w < np; ++w) test(w);
          return;
        }
        // the other primitives and the triangles of x's bin, merged in ascending order
        const std::uint32_t *other = bins.others().data(), *otherEnd = other + bins.others().size();
        auto [triangle, triangleEnd] = bins.trianglesNear(x);
        while (other != otherEnd || triangle != triangleEnd)
          test(triangle == triangleEnd || (other != otherEnd && *other < *triangle) ? *other++ : *triangle++);
      },
      [&](std::size_t m) {
        tangentialHistory.assign(m, Vec3{});
        rollingHistory.assign(withRollingHistory ? m : 0, Vec3{});
        force.assign(m, Vec3{});
        point.assign(m, Vec3{});
        particle.resize(m);
      },
      [&](std::size_t i) {  // history carried over by (particle, primitive)
        assignRowParticle(i);
        const std::int64_t oi = i < previousIndex.size() ? previousIndex[i] : -1;
        if (oi < 0 || oi >= oldRows) return;
        for (std::uint32_t k = rowStart[i]; k < rowStart[i + 1]; ++k)
          for (std::uint32_t q = oldStart[oi]; q < oldStart[oi + 1]; ++q)
            if (oldPrimitive[q] == primitive[k]) {
              tangentialHistory[k] = oldTangential[q];
              if (carryRolling) rollingHistory[k] = oldRolling[q];
              break;
            }
      });
}

void WallContactList::save(BinaryWriter& out) const {
  out.putVector(rowStart);
  out.putVector(primitive);
  out.putVector(tangentialHistory);
  out.putVector(rollingHistory);
  out.putVector(force);
  out.putVector(point);
}

void WallContactList::load(BinaryReader& in) {
  rowStart = in.getVector<std::uint32_t>();
  primitive = in.getVector<std::uint32_t>();
  tangentialHistory = in.getVector<Vec3>();
  rollingHistory = in.getVector<Vec3>();
  force = in.getVector<Vec3>();
  point = in.getVector<Vec3>();
  if (tangentialHistory.size() != primitive.size() || force.size() != primitive.size() ||
      (!rowStart.empty() && rowStart.back() != primitive.size()))
    throw CheckpointError("checkpoint is corrupt: DEM wall contact arrays do not match");
  particle.resize(primitive.size());
  for (std::size_t i = 0; i + 1 < rowStart.size(); ++i) assignRowParticle(i);
}

}  // namespace gf::dem
