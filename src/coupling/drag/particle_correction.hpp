#pragma once
// A drag law evaluated with per-particle data besides (Re, eps): the polydisperse laws (size ratio
// y_i and the mixture Reynolds number of the particle's cell, seed 003 sec. 3.1.3) and the filtered
// correction on top of a Beetstra law (filtered.hpp). The coupler resolves to this functor only
// when one of them is selected; every other case keeps its monomorphic functor (dispatch.hpp).
#include <cstddef>
#include <cstdint>

#include "coupling/drag/drag_law.hpp"
#include "coupling/drag/filtered.hpp"

namespace gf::coupling {

struct ParticleCorrection {
  const DragLaw* law = nullptr;
  const double* sizeRatio = nullptr;        // per particle, polydisperse laws only
  const double* mixtureReynolds = nullptr;  // per particle (its cell's), polydisperse laws only
  bool filtered = false;
  double filterSize = 0.0;            // Delta, m
  double characteristicLength = 0.0;  // L_char, m
  double parcelCorrection = 1.0;      // c_corr(alpha)
  // coarse graining per insertion: c_corr of each material's alpha, indexed by material[p]
  const double* parcelCorrectionByMaterial = nullptr;
  const std::int32_t* material = nullptr;

  /// f[q] for particles begin + q, q in [0, n), at re[q], eps[q].
  void block(std::size_t begin, const double* re, const double* eps, double* f, int n) const {
    for (int q = 0; q < n; ++q) {
      const std::size_t p = begin + static_cast<std::size_t>(q);
      double v = sizeRatio ? law->polydisperseCorrection(re[q], eps[q], sizeRatio[p], mixtureReynolds[p])
                           : law->correction(re[q], eps[q]);
      if (filtered)
        v *= (parcelCorrectionByMaterial ? parcelCorrectionByMaterial[material[p]] : parcelCorrection) * drag::filteredDragCorrection(1.0 - eps[q], filterSize, characteristicLength);
      f[q] = v;
    }
  }
};

}  // namespace gf::coupling
