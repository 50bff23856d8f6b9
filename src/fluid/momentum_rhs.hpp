#pragma once
// Right-hand side of the eps-varying momentum predictor at one face point (BDF2/EX2, Karniadakis,
// Israeli & Orszag 1991; VANS model A/B of seeds 000 §5.1 and 001): used by
// Solver::assembleMomentum and, fused with the convection pass, by predictMomentumTeam (the same
// arithmetic in both: bit-identical results).
#include <cstddef>

namespace gf::fluid {

struct MomentumRhsPoint {
  const double *U, *Uo, *No, *P, *E, *En, *Enm, *F, *K, *Up;
  std::ptrdiff_t se;  // cell stride along the component
  double invH, rdt, g1, g2, e1, e2, rho, gc, drive;
  bool modelA;

  /// b at face point f (cells cc above and cc - se below it) with this step's convection Nf.
  [[gnu::always_inline]] double operator()(std::size_t f, std::size_t cc, double Nf) const {
    const std::size_t cm = cc - se;
    const double epsF = 0.5 * (E[cc] + E[cm]);
    const double epsN = 0.5 * (En[cc] + En[cm]);
    const double epsNm = 0.5 * (Enm[cc] + Enm[cm]);
    const double a = modelA ? epsF : 1.0;
    double r = rdt * (g1 * epsN * U[f] - g2 * epsNm * Uo[f]);
    r -= e1 * Nf - e2 * No[f];
    r -= a * (P[cc] - P[cm]) * invH;
    r += epsF * rho * gc + a * drive;
    r += 0.5 * (F[cc] + F[cm]) + 0.5 * (K[cc] * Up[cc] + K[cm] * Up[cm]);
    return r;
  }
};

}  // namespace gf::fluid
