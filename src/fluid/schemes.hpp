#pragma once
// Face interpolation of a transported quantity: second-order central and the van Leer TVD
// scheme (van Leer 1974; limiter psi(r) = (r + |r|) / (1 + |r|), written in the harmonic-mean
// form that needs no division by a possibly zero gradient).
namespace gf::fluid {

/// van Leer limited slope from the upwind difference a and the downwind difference b.
inline double vanLeerSlope(double a, double b) { return a * b > 0.0 ? 2.0 * a * b / (a + b) : 0.0; }

/// Value at the face between points q0 and q1 (qm before q0, q2 after q1) for flux `flux`
/// (positive from q0 towards q1).
template <bool TVD>
inline double faceValue(double flux, double qm, double q0, double q1, double q2) {
  if constexpr (!TVD) {
    return 0.5 * (q0 + q1);
  } else {
    // The two cases of q0 + 0.5 vanLeerSlope(q0 - qm, q1 - q0) (flux >= 0) and
    // q1 + 0.5 vanLeerSlope(q1 - q2, q0 - q1) (flux < 0) written as selections (the same
    // arithmetic, branch-free: the flux and slope signs of a bubbling bed mispredict).
    const bool up = flux >= 0.0;
    const double a = up ? q0 - qm : q1 - q2;
    const double b = up ? q1 - q0 : q0 - q1;
    const double base = up ? q0 : q1;
    const double harmonic = 2.0 * a * b / (a + b);  // vanLeerSlope's value where a b > 0
    const double slope = a * b > 0.0 ? harmonic : 0.0;
    return base + 0.5 * slope;
  }
}

}  // namespace gf::fluid
