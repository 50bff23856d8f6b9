#pragma once
// Weights of each particle over the fluid cells ("stencil"). One stencil serves three purposes:
// the particle volume fraction (eps), optionally the interpolation to the particle, and the
// distribution of the particle forces back to the fluid. Weights of a particle sum to 1 (to
// round-off), so every deposit conserves the deposited quantity exactly.
//
// Storage: fixed capacity per particle (flat arrays, SoA), count[p] entries used.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gf::coupling {

struct ParticleStencils {
  int capacity = 0;
  std::vector<int> count;           // entries used per particle
  std::vector<std::size_t> cell;    // flat cell index (Field::index), particle p at [p*capacity, ...)
  std::vector<double> weight;       // sums to 1 per particle

  void resize(std::size_t particles, int entriesPerParticle) {
    capacity = entriesPerParticle;
    count.assign(particles, 0);
    cell.resize(particles * static_cast<std::size_t>(capacity));
    weight.resize(particles * static_cast<std::size_t>(capacity));
  }
  std::size_t size() const { return count.size(); }
};

/// The stencils of a piece of consecutive particles, wherever they are stored: the piece's first
/// particle has count[0] entries at cell[0..), weight[0..); particle q of the piece at q * capacity.
struct StencilPiece {
  const int* count;
  const std::size_t* cell;
  const double* weight;
  std::size_t capacity;
  /// The piece of `s` that starts at particle `first`.
  static StencilPiece of(const ParticleStencils& s, std::size_t first) {
    const auto capacity = static_cast<std::size_t>(s.capacity);
    return {s.count.data() + first, s.cell.data() + first * capacity, s.weight.data() + first * capacity, capacity};
  }
};

/// Writes the stencil of one particle; merges repeated cells. Owned by one thread per particle.
class StencilWriter {
 public:
  StencilWriter(ParticleStencils& s, std::size_t particle)
      : cell_(s.cell.data() + particle * s.capacity), weight_(s.weight.data() + particle * s.capacity),
        count_(s.count[particle]), capacity_(s.capacity) {
    count_ = 0;
  }
  void add(std::size_t cell, double w) {
    for (int e = 0; e < count_; ++e) {
      if (cell_[e] == cell) {
        weight_[e] += w;
        return;
      }
    }
    if (count_ < capacity_) {
      cell_[count_] = cell;
      weight_[count_] = w;
      ++count_;
    }
  }
  /// Adds an entry known to be new (no search).
  void append(std::size_t cell, double w) {
    if (count_ < capacity_) {
      cell_[count_] = cell;
      weight_[count_] = w;
      ++count_;
    }
  }
  /// Appends the entry if `keep`, without a branch: the entry is written in any case (the caller
  /// guarantees capacity for every call, kept or not) and counted only if kept.
  void appendIf(bool keep, std::size_t cell, double w) {
    cell_[count_] = cell;
    weight_[count_] = w;
    count_ += keep ? 1 : 0;
  }
  /// Scales the weights to sum 1; returns the sum before (0 if empty).
  double normalise() {
    double sum = 0.0;
    for (int e = 0; e < count_; ++e) sum += weight_[e];
    if (sum > 0.0)
      for (int e = 0; e < count_; ++e) weight_[e] /= sum;
    return sum;
  }
  int count() const { return count_; }

 private:
  std::size_t* cell_;
  double* weight_;
  int& count_;
  int capacity_;
};

}  // namespace gf::coupling
