#include "coupling/size_classes.hpp"

#include <algorithm>
#include <cmath>

#include "coupling/forces.hpp"

namespace gf::coupling {

SizeClasses::SizeClasses(std::vector<double> d) {
  std::sort(d.begin(), d.end());
  d.erase(std::unique(d.begin(), d.end()), d.end());
  if (static_cast<int>(d.size()) <= kMaxSizeClasses) {
    diameters_ = std::move(d);
    return;
  }
  binned_ = true;
  logMin_ = std::log(d.front());
  logWidth_ = (std::log(d.back()) - logMin_) / kMaxSizeClasses;
  for (int i = 0; i < kMaxSizeClasses; ++i) diameters_.push_back(std::exp(logMin_ + (i + 0.5) * logWidth_));
}

int SizeClasses::classOf(double d) const {
  if (diameters_.empty()) return 0;
  if (binned_) {
    const int i = static_cast<int>(std::floor((std::log(d) - logMin_) / logWidth_));
    return std::clamp(i, 0, kMaxSizeClasses - 1);
  }
  const auto it = std::lower_bound(diameters_.begin(), diameters_.end(), d);
  if (it == diameters_.begin()) return 0;
  if (it == diameters_.end()) return static_cast<int>(diameters_.size()) - 1;
  const auto i = static_cast<int>(it - diameters_.begin());
  return (*it - d) < (d - *(it - 1)) ? i : i - 1;
}

void computeCellSizeStatistics(const GridTopology& topology, const dem::ParticleSet& particles,
                               const CoarseGraining& coarseGraining, const SizeClasses& classes, CellSizeStatistics& out,
                               std::vector<std::size_t>& cellOfParticle, std::vector<int>& classOfParticle,
                               bool classVelocities, const std::uint8_t* skip) {
  const CartesianGrid& g = topology.grid;
  const std::size_t cells = static_cast<std::size_t>(g.cells[0] + 2 * g.ghosts) *
                            static_cast<std::size_t>(g.cells[1] + 2 * g.ghosts) *
                            static_cast<std::size_t>(g.cells[2] + 2 * g.ghosts);
  out.classes = std::max(classes.count(), 1);
  out.cellVolume = g.cellVolume();
  out.solidVolume.assign(cells, 0.0);
  out.volumeOverDiameter.assign(cells, 0.0);
  out.volumeVelocity.assign(cells, Vec3{});
  out.classVolume.assign(cells * static_cast<std::size_t>(out.classes), 0.0);
  if (classVelocities) out.classVolumeVelocity.assign(cells * static_cast<std::size_t>(out.classes), Vec3{});
  else out.classVolumeVelocity.clear();
  const std::size_t n = particles.size();
  cellOfParticle.resize(n);
  classOfParticle.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    const double d = 2.0 * particles.radius[p];
    const double primary = d / coarseGraining.factorOf(particles.type[p]);
    const double volume = force::sphereVolume(d);
    const auto c = topology.cellOf(particles.position[p]);
    const std::size_t q = topology.flat(c[0], c[1], c[2]);
    const int i = classes.classOf(primary);
    cellOfParticle[p] = q;
    classOfParticle[p] = i;
    if (skip && skip[p]) continue;
    out.solidVolume[q] += volume;
    out.volumeOverDiameter[q] += volume / primary;
    out.volumeVelocity[q] += volume * particles.velocity[p];
    const std::size_t k = q * static_cast<std::size_t>(out.classes) + static_cast<std::size_t>(i);
    out.classVolume[k] += volume;
    if (classVelocities) out.classVolumeVelocity[k] += volume * particles.velocity[p];
  }
}

}  // namespace gf::coupling
