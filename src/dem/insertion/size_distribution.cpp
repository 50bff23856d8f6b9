#include "dem/insertion/size_distribution.hpp"

namespace gf::dem {

std::unique_ptr<SizeDistribution> readSizeDistribution(Params& p) {
  // Shortcut: a plain `diameter` key means monodisperse particles.
  if (p.has("diameter") && !p.has("size")) return Registry<SizeDistribution>::instance().createByName("constant", p);
  Params s = p.section({"size", "-", "particle size distribution"});
  return Registry<SizeDistribution>::instance().create(s, {"distribution", "-", "size distribution model"},
                                                       "constant");
}

}  // namespace gf::dem
