// Particles on a simple cubic lattice.
#include <fmt/format.h>

#include "dem/insertion/inserter.hpp"

namespace gf::dem {
namespace {
class LatticeInsertion final : public Inserter {
 public:
  explicit LatticeInsertion(Params& p) : common_(p) {
    origin_ = p.vec3({"origin", "m", "lattice: centre of the first particle"}, {});
    spacing_ = p.real({"spacing", "m", "lattice: distance between neighbouring centres", Range::positive()}, 0.003);
    for (int a = 0; a < 3; ++a) {
      static constexpr const char* names[3] = {"nx", "ny", "nz"};
      count_[a] = static_cast<int>(p.integer({names[a], "-", "lattice: particles along this axis", Range::atLeast(1)}, 1));
    }
    if (!p.documenting() && common_.size->maxDiameter() > spacing_)
      p.fail("spacing", fmt::format("{:g} m", spacing_),
             fmt::format("at least the largest diameter {:g} m", common_.size->maxDiameter()));
    params_ = p;
  }
  std::size_t insert(InsertionContext& ctx, double, double) override {
    if (done_) return 0;
    done_ = true;
    std::size_t added = 0;
    for (int k = 0; k < count_[2]; ++k)
      for (int j = 0; j < count_[1]; ++j)
        for (int i = 0; i < count_[0]; ++i) {
          const Vec3 x = origin_ + spacing_ * Vec3{double(i), double(j), double(k)};
          if (!ctx.domain.contains(x))
            params_.fail("origin", fmt::format("a particle at ({:g}, {:g}, {:g}) outside the domain", x.x, x.y, x.z),
                         "all lattice points inside 'domain'");
          const double d = common_.size->sample(common_.rng);
          ctx.particles.add(ctx.nextId++, common_.material, 0.5 * d, common_.density, x, common_.velocity);
          ++added;
        }
    return added;
  }
  SmallestInserted smallest() const override { return common_.smallest(); }
  void save(BinaryWriter& out) const override { out.put<std::uint8_t>(done_); }
  void load(BinaryReader& in) override { done_ = in.get<std::uint8_t>() != 0; }

  double coarseGraining() const override { return common_.coarseGraining; }
  int material() const override { return common_.material; }

 private:
  InsertionCommon common_;
  Vec3 origin_;
  double spacing_ = 0.0;
  int count_[3] = {1, 1, 1};
  bool done_ = false;
  Params params_ = Params::documentation();
};
}  // namespace
}  // namespace gf::dem

GF_REGISTER_MODEL(gf::dem::Inserter, gf::dem::LatticeInsertion, "lattice",
                  "simple cubic lattice (origin, spacing, nx, ny, nz)")
