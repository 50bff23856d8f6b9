#pragma once
// Coarse graining: a parcel of diameter d = k d_prim stands for k^3 primary particles (same
// density, same total volume). Scaling used (Bierwisch et al. 2009; Radl et al. 2011; seed 003
// eq. 3.34 with alpha = k):
//   fluid forces   F_parcel = k^3 F_prim(d_prim, same slip)  -> beta_parcel = k^3 beta_prim;
//                  Re and the drag law use d_prim; pressure/viscous/virtual-mass forces scale with
//                  the parcel volume (already k^3 V_prim).
//   contacts       geometric similarity (same overlap/diameter under the same stress): Hertz
//                  keeps E, nu; a linear spring scales k_n, k_t by k; restitution and friction are
//                  kept, so a linear dashpot (c = 2 zeta sqrt(m k_n)) scales by k^2.
// A parcel then settles at the terminal velocity of a primary particle (test).
namespace gf::coupling {

struct CoarseGraining {
  double factor = 1.0;  // k >= 1

  double primaryDiameter(double parcelDiameter) const { return parcelDiameter / factor; }
  double particlesPerParcel() const { return factor * factor * factor; }
  double fluidForceScale() const { return particlesPerParcel(); }
  double hertzModulusScale() const { return 1.0; }
  double linearStiffnessScale() const { return factor; }
  double linearDampingScale() const { return factor * factor; }
};

}  // namespace gf::coupling
