#pragma once
// Size classes and per-cell size statistics of the particles (seed 003 sec. 3.1.1): what the
// polydisperse drag laws need (the Sauter mean diameter <d> and the mixture slip of each cell)
// and what monitors report per class (each class's solid volume fraction phi_i).
//
// A size class is one distinct primary diameter (parcel diameter / coarse-graining factor), in
// ascending order. The insertions draw diameters from their `size` distribution; the discrete one
// (the seed's Tab. 3.2 distribution) gives one class per listed diameter, so the class is the
// entry of the distribution. It is a function of the diameter alone: the coupler derives it from
// the particles (column kSizeClassColumn, written when the statistics are computed) instead of the
// inserter storing it, so the particle layout and the insertions stay as they are. Continuous
// distributions (log_normal, rosin_rammler) give every particle its own diameter: beyond
// kMaxSizeClasses distinct diameters the classes are kMaxSizeClasses bins of equal width in ln d
// between the smallest and the largest diameter.
//
// Per cell (the cell holding the particle's centre; parcel volumes V_p, primary diameters d_p):
//   phi_i = sum_{p in class i} V_p / V_cell                               (eq. 3.1)
//   <d>   = sum V_p / sum (V_p / d_p) = [sum_i phi_i / d_i / phi]^-1      (eq. 3.5)
//   <v>   = sum V_p v_p / sum V_p, the mixture slip u_f - <v>             (eq. 3.28)
// Computed only when a polydisperse law (or a monitor) asks for them: one pass over the particles.
#include <cstddef>
#include <vector>

#include "coupling/coarse_graining.hpp"
#include "coupling/grid_topology.hpp"
#include "dem/particles.hpp"

namespace gf::coupling {

class SizeClasses {
 public:
  static constexpr int kMaxSizeClasses = 16;
  SizeClasses() = default;
  /// The classes of these primary diameters (any order, repeats allowed).
  explicit SizeClasses(std::vector<double> primaryDiameters);
  int count() const { return binned_ ? kMaxSizeClasses : static_cast<int>(diameters_.size()); }
  /// Whether the classes are bins in ln d (more distinct diameters than kMaxSizeClasses).
  bool binned() const { return binned_; }
  /// The class of a primary diameter: the nearest distinct diameter (or its bin, clamped).
  int classOf(double primaryDiameter) const;
  /// The distinct diameters (unbinned) or the bins' geometric centres (binned), m.
  const std::vector<double>& diameters() const { return diameters_; }

 private:
  std::vector<double> diameters_;
  bool binned_ = false;
  double logMin_ = 0.0, logWidth_ = 1.0;
};

struct CellSizeStatistics {
  int classes = 0;
  double cellVolume = 1.0;
  // per flat index of a cell-centred field (interior cells written, ghosts zero)
  std::vector<double> solidVolume;         // sum V_p, m^3
  std::vector<double> volumeOverDiameter;  // sum V_p / d_p, m^2
  std::vector<Vec3> volumeVelocity;        // sum V_p v_p, m^4/s
  std::vector<double> classVolume;         // [q * classes + i]: sum V_p of class i, m^3
  std::vector<Vec3> classVolumeVelocity;   // [q * classes + i]: sum V_p v_p of class i (if asked for), m^4/s

  /// <d> of cell q (0 if it holds no particle), m.
  double sauterDiameter(std::size_t q) const {
    return volumeOverDiameter[q] > 0.0 ? solidVolume[q] / volumeOverDiameter[q] : 0.0;
  }
  double volumeFraction(std::size_t q) const { return solidVolume[q] / cellVolume; }
  double classVolumeFraction(std::size_t q, int i) const {
    return classVolume[q * static_cast<std::size_t>(classes) + static_cast<std::size_t>(i)] / cellVolume;
  }
  /// Mean velocity of class i in cell q (zero if absent; needs classVolumeVelocity), m/s.
  Vec3 classVelocity(std::size_t q, int i) const {
    const std::size_t k = q * static_cast<std::size_t>(classes) + static_cast<std::size_t>(i);
    return classVolume[k] > 0.0 ? (1.0 / classVolume[k]) * classVolumeVelocity[k] : Vec3{};
  }
  /// <v> of cell q (zero if empty), m/s.
  Vec3 meanParticleVelocity(std::size_t q) const {
    return solidVolume[q] > 0.0 ? (1.0 / solidVolume[q]) * volumeVelocity[q] : Vec3{};
  }
};

/// Fills `out` for `particles` (cells: cell-centred fields of `topology`); cellOfParticle[p] is the
/// flat index of particle p's cell, classOfParticle[p] its class; classVelocities: also
/// classVolumeVelocity (else left empty). `skip` (optional, per particle): particles whose entry is
/// nonzero get their cell and class but add nothing to the sums (MPI ghosts: their owner adds them).
void computeCellSizeStatistics(const GridTopology& topology, const dem::ParticleSet& particles,
                               const CoarseGraining& coarseGraining, const SizeClasses& classes, CellSizeStatistics& out,
                               std::vector<std::size_t>& cellOfParticle, std::vector<int>& classOfParticle,
                               bool classVelocities = false, const std::uint8_t* skip = nullptr);

}  // namespace gf::coupling
