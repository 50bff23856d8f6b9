#pragma once
// Coarse graining: a parcel of diameter d = k d_prim stands for k^3 primary particles (same
// density, same total volume). Scaling used (Bierwisch et al. 2009; Radl et al. 2011; seed 003
// eq. 3.34 with alpha = k):
//   fluid forces   F_parcel = k^3 F_prim(d_prim, same slip)  -> beta_parcel = k^3 beta_prim;
//                  Re and the drag law use d_prim; pressure/viscous/virtual-mass forces scale with
//                  the parcel volume (already k^3 V_prim).
//   contacts       geometric similarity (same overlap/diameter under the same stress): Hertz
//                  keeps E, nu; a linear spring scales k_n, k_t by k; restitution and friction are
//                  kept, so a linear dashpot (c = 2 zeta sqrt(m k_n)) scales by k^2. Seed 003 runs
//                  its alpha = 10 boxes with the Hertz model and the material data of the primary
//                  particles (Tab. 4.3 for every alpha, sec. 4.1.1): with Hertz nothing changes.
// A parcel then settles at the terminal velocity of a primary particle (test).
//
// The factor is per insertion (insertion[].coarse_graining), carried by the particles' material:
// byMaterial[m] is the factor of the particles of material m (the insertions that make material m
// share one factor, the DEM checks it); empty: `factor` for every particle
// (coupling.coarse_grain_factor, the default of the insertions that set none).
#include <algorithm>
#include <cstdint>
#include <vector>

namespace gf::coupling {

struct CoarseGraining {
  CoarseGraining() = default;
  explicit CoarseGraining(double k) : factor(k) {}

  double factor = 1.0;  // k >= 1
  std::vector<double> byMaterial;         // k per material index (empty: `factor` for all)
  std::vector<double> inverseByMaterial;  // 1 / byMaterial[m]
  std::vector<double> particlesPerParcelByMaterial;  // byMaterial[m]^3

  double primaryDiameter(double parcelDiameter) const { return parcelDiameter / factor; }
  double particlesPerParcel() const { return factor * factor * factor; }
  double fluidForceScale() const { return particlesPerParcel(); }
  double hertzModulusScale() const { return 1.0; }
  double linearStiffnessScale() const { return factor; }
  double linearDampingScale() const { return factor * factor; }

  /// Factors per material: the ones given (> 0), `factor` for the materials no insertion sets
  /// (0). All equal: kept as the one `factor` (the per-particle lookups are skipped).
  void setByMaterial(const std::vector<double>& given) {
    byMaterial.assign(given.size(), factor);
    for (std::size_t m = 0; m < given.size(); ++m)
      if (given[m] > 0.0) byMaterial[m] = given[m];
    const bool uniform = byMaterial.empty() || std::all_of(byMaterial.begin(), byMaterial.end(),
                                                           [&](double k) { return k == byMaterial.front(); });
    if (uniform) {
      if (!byMaterial.empty()) factor = byMaterial.front();
      byMaterial.clear();
      inverseByMaterial.clear();
      particlesPerParcelByMaterial.clear();
      return;
    }
    inverseByMaterial.resize(byMaterial.size());
    particlesPerParcelByMaterial.resize(byMaterial.size());
    for (std::size_t m = 0; m < byMaterial.size(); ++m) {
      inverseByMaterial[m] = 1.0 / byMaterial[m];
      particlesPerParcelByMaterial[m] = byMaterial[m] * byMaterial[m] * byMaterial[m];
    }
  }
  bool uniform() const { return byMaterial.empty(); }
  /// k of a particle of material `material`.
  double factorOf(std::int32_t material) const {
    return byMaterial.empty() ? factor : byMaterial[static_cast<std::size_t>(material)];
  }
  /// The largest k of any material.
  double largest() const {
    return byMaterial.empty() ? factor : *std::max_element(byMaterial.begin(), byMaterial.end());
  }
};

}  // namespace gf::coupling
