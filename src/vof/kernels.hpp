#pragma once
// Pure formulas of the phase-fraction transport (src/vof/transport.cpp): functions of plain numbers,
// shared by the loops of one box and, later, device kernels.
#include <algorithm>
#include <cmath>

namespace gf::vof::kernels {

/// Lax-Wendroff part of a face value beyond upwind: the transported face value is
/// alpha_up + 0.5 (1 - c)(alpha_down - alpha_up), second order in space and time for a uniform
/// velocity (Lax & Wendroff 1960; the high-order flux of Zalesak's FCT, J. Comput. Phys. 31, 1979).
/// c = |phi| dt / (eps_up h) is the face's Courant number (clipped to [0, 1]).
inline double laxWendroffIncrement(double alphaUp, double alphaDown, double courant) {
  const double c = std::clamp(courant, 0.0, 1.0);
  return 0.5 * (1.0 - c) * (alphaDown - alphaUp);
}

/// Normal component along one axis of the unit interface normal between phases i and j at a face,
/// from the face mean g of alpha_j grad alpha_i - alpha_i grad alpha_j (the pair normal of
/// OpenFOAM's multiphaseMixture::nHatfv): g_a / (|g| + delta), delta = 1e-8 / h keeping the
/// normal finite where the fractions are uniform (OpenFOAM's deltaN).
inline double pairNormal(double gx, double gy, double gz, int axis, double delta) {
  const double g[3] = {gx, gy, gz};
  return g[axis] / (std::sqrt(gx * gx + gy * gy + gz * gz) + delta);
}

/// Compression flux (m/s) of phase i towards phase j's complement through a face, the pair form of
/// seed 002 eq. 2 (line 316, Rusche 2002): phi_r alpha_i,up alpha_j,down with the compression face
/// velocity phi_r = C |phi| n_ij,a, alpha_i taken upwind and alpha_j downwind of phi_r (as
/// OpenFOAM's alphaEqn: fvc::flux(-fvc::flux(-phir, alpha2), alpha1)). Summed over j != i it is
/// the seed's u_c alpha_i (1 - alpha_i) for two phases, alpha_j = 1 - alpha_i; the flux of the pair
/// (j, i) is its negative, so the compression of all phases sums to zero on every face.
inline double pairCompressionFlux(double phiR, double alphaIP, double alphaIN, double alphaJP, double alphaJN) {
  return phiR >= 0.0 ? phiR * alphaIP * alphaJN : phiR * alphaIN * alphaJP;
}

/// Zalesak's ratio R = min(1, Q / P) (J. Comput. Phys. 31, 1979, eqs. 7-12): the share of the
/// antidiffusive fluxes P into (R+) or out of (R-) a cell that keeps it within its bound Q.
/// No such flux (P = 0): 1 (then no face asks for it).
inline double zalesakRatio(double q, double p) {
  if (p <= 0.0) return 1.0;
  return std::min(1.0, std::max(q, 0.0) / p);
}

/// Zalesak's face factor of a correction `a` from the lower cell L to the upper cell U (eq. 13):
/// a >= 0 enters U and leaves L, so C = min(R+_U, R-_L); otherwise C = min(R+_L, R-_U).
inline double faceFactor(double a, double rPlusL, double rMinusL, double rPlusU, double rMinusU) {
  return a >= 0.0 ? std::min(rPlusU, rMinusL) : std::min(rPlusL, rMinusU);
}

/// Makes the limited corrections of the N phases at one face sum to zero by scaling down the side
/// (positive or negative) that is larger, as OpenFOAM's MULES::limitSum: every correction keeps
/// its sign and shrinks, so each phase stays within the bounds its limiter guaranteed, and the
/// phases' fluxes add up to the upwind fluxes, whose sum is the mixture's flux.
inline void limitSum(double* c, int phases) {
  double pos = 0.0, neg = 0.0;
  for (int i = 0; i < phases; ++i) (c[i] > 0.0 ? pos : neg) += c[i];
  const double sum = pos + neg;
  if (sum > 0.0 && pos > 0.0) {
    const double f = -neg / pos;
    for (int i = 0; i < phases; ++i)
      if (c[i] > 0.0) c[i] *= f;
  } else if (sum < 0.0 && neg < 0.0) {
    const double f = -pos / neg;
    for (int i = 0; i < phases; ++i)
      if (c[i] < 0.0) c[i] *= f;
  }
}

}  // namespace gf::vof::kernels
