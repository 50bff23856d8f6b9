#pragma once
// Direct forcing of one rigid body on the staggered (MAC) face velocities: the kernel of the
// fictitious-domain step (seed 000 lines 471-510) and of the hydrodynamic force (lines 411-464).
//
// Each face velocity of component c at x_f has a control volume, the box of one cell size centred on
// x_f; phi is the fraction of that box the body covers (overlap.hpp, smooth). After the momentum
// predictor the face velocity u-hat is replaced by
//     u-tilde = u-hat + phi (u_b(x_f) - u-hat),   u_b = U + omega x (x_f - X)         (seed eq. 2.5)
// which is the body force f = rho gamma0 (u-tilde - u-hat) / dt on the fluid (seed eq. 2.9 with the
// BDF time derivative gamma0 / dt of the fluid solver). The force of the forcing on the body is
// -sum f V_f, its torque -sum (x_f - X) x f V_f: the discrete volume integral of seed eq. 2.25, taken
// over the cells the body covers, as in Uhlmann (2005, J. Comput. Phys. 209, eq. 20).
// The momentum of the fluid inside the body, I = sum phi u V_f (and its moment sum phi (x_f - X) x u
// V_f), gives the rigid-body correction rho dI/dt of the force (Kempe & Froehlich 2012, J. Comput.
// Phys. 231, eq. 8; Breugem 2012, eq. 13): the fluid inside a moving body accelerates with it, which
// the forcing alone does not see.
#include <array>
#include <cstdint>
#include <memory>

#include "core/grid.hpp"
#include "core/vec3.hpp"
#include "resolved/mesh_body.hpp"
#include "resolved/overlap.hpp"

namespace gf::resolved {

enum class Shape : std::uint8_t { Sphere, Cylinder, Mesh };

/// A body as the forcing sees it for one step.
struct Body {
  Shape shape = Shape::Sphere;
  Vec3 centre;           // m; a cylinder: a point of its axis, which is parallel to z; a mesh: the point
                         // its torque is taken about and its rotation's centre
  double radius = 0.0;   // m; a mesh: the radius of the sphere of its volume
  Vec3 velocity;         // m/s, U
  Vec3 angularVelocity;  // rad/s, omega
  std::shared_ptr<const MeshBody> mesh;  // Shape::Mesh: the closed triangle mesh and its fractions
};

/// Rigid-body velocity at x (seed eq. 2.5).
inline Vec3 rigidVelocity(const Body& b, const Vec3& x) { return b.velocity + cross(b.angularVelocity, x - b.centre); }

/// Fraction of the box [lo, hi] covered by the body.
inline double coveredFraction(const Body& b, const Vec3& lo, const Vec3& hi) {
  switch (b.shape) {
    case Shape::Sphere:
      return sphereBoxFraction(b.centre, b.radius, lo, hi);
    case Shape::Cylinder:
      return cylinderBoxFraction(b.centre, b.radius, lo, hi);
    case Shape::Mesh:
      return b.mesh->fraction(lo, hi);
  }
  return 0.0;
}

/// Lower and upper corner of a box that holds the body (a cylinder: its disk in x-y, centre.z +-
/// radius along z, which a 2D grid ignores).
inline void bodyBounds(const Body& b, Vec3& lo, Vec3& hi) {
  if (b.shape == Shape::Mesh) {
    lo = b.mesh->lower();
    hi = b.mesh->upper();
    return;
  }
  lo = b.centre - Vec3{b.radius, b.radius, b.radius};
  hi = b.centre + Vec3{b.radius, b.radius, b.radius};
}

/// Volume of the body inside a domain of extent `depth` along z (a cylinder), m^3.
inline double bodyVolume(const Body& b, double depth) {
  constexpr double kPi = 3.14159265358979323846;
  if (b.shape == Shape::Mesh) return b.mesh->volume();
  return b.shape == Shape::Sphere ? 4.0 / 3.0 * kPi * b.radius * b.radius * b.radius : kPi * b.radius * b.radius * depth;
}

/// Where the faces of one rank's box are forced and counted.
struct FaceBox {
  CartesianGrid grid;                  // this rank's grid (origin: its lower corner)
  std::array<int, 3> offset{0, 0, 0};  // its first cell in the whole grid
  std::array<int, 3> global{1, 1, 1};  // cells of the whole grid
  std::array<bool, 3> periodic{false, false, false};
  bool twoD = false;  // one cell along z: the w faces are not forced, a cylinder spans all of z
};

/// Sums over the faces a body covers.
struct FaceSums {
  Vec3 force;            // N: the forcing's force on the body, -sum f V (forcing pass)
  Vec3 torque;           // N m, about the body's centre
  Vec3 momentum;         // kg m/s / rho: sum phi u V (momentum pass)
  Vec3 angularMomentum;  // sum phi (x - X) x u V
};

/// Calls body(c, i, j, k, x, phi) for every face point of component c (this rank's box) whose
/// control volume the body covers (phi > 0) and that the forcing may change (not a face on a
/// non-periodic boundary of the whole grid); `counted` is false for the duplicate face n of a
/// periodic axis / the face shared with the next rank (forced, not summed).
template <class Visit>
void forEachCoveredFace(const Body& b, const FaceBox& box, Visit&& visit) {
  const CartesianGrid& g = box.grid;
  const Vec3 h = g.spacing;
  Vec3 blo, bhi;
  bodyBounds(b, blo, bhi);
  for (int c = 0; c < (box.twoD ? 2 : 3); ++c) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const int n = g.cells[a] + (a == c ? 1 : 0);  // face points along a
      if (box.twoD && a == 2) {
        lo[a] = 0;
        hi[a] = n - 1;
        continue;
      }
      const double shift = a == c ? 0.0 : 0.5;  // face point i at origin + (i + shift) h
      lo[a] = std::max(0, static_cast<int>(std::floor((blo[a] - g.origin[a]) / h[a] - shift)) - 1);
      hi[a] = std::min(n - 1, static_cast<int>(std::ceil((bhi[a] - g.origin[a]) / h[a] - shift)) + 1);
    }
    const int gi0 = box.offset[c], N = box.global[c];
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const int idx[3] = {i, j, k};
          const int gNormal = gi0 + idx[c];
          if (!box.periodic[c] && (gNormal == 0 || gNormal == N)) continue;  // boundary face: the BC's
          Vec3 x, clo, chi;
          for (int a = 0; a < 3; ++a) {
            x[a] = g.origin[a] + (idx[a] + (a == c ? 0.0 : 0.5)) * h[a];
            clo[a] = x[a] - 0.5 * h[a];
            chi[a] = x[a] + 0.5 * h[a];
          }
          const double phi = coveredFraction(b, clo, chi);
          if (phi <= 0.0) continue;
          const bool counted = idx[c] < g.cells[c];
          visit(c, i, j, k, x, phi, counted);
        }
  }
}

/// Penalty coefficient of a cell the body covers by fraction phi (implicit forcing): the fluid
/// feels K (u_b - u) in its momentum predictor and in the projection (fluid::Solver's implicit drag
/// term, CouplingFields::dragCoefficient). With D the diagonal of the predictor's operator at a
/// face, D = rho gamma0 / dt + 2 dims mu / h^2, K = D phi / (1 - phi) makes the face's velocity the
/// weighted mean (1 - phi) u_rest + phi u_b of what the rest of the equation gives and the body's
/// velocity: the weighting of the smooth representation (seed 000 lines 589-598) whatever the
/// viscous number nu dt / h^2. Capped at kMaxPenalty D in covered cells (there u = u_b to
/// 1 / kMaxPenalty).
inline constexpr double kMaxPenalty = 1.0e4;
inline double penaltyCoefficient(double phi, double diagonal) {
  return phi >= 1.0 ? kMaxPenalty * diagonal : std::min(kMaxPenalty, phi / (1.0 - phi)) * diagonal;
}
/// D of penaltyCoefficient: rho gamma0 / dt + 2 dims mu / h^2 (h: the smallest spacing).
inline double predictorDiagonal(double rho, double mu, double gamma0, double dt, const Vec3& h, bool twoD) {
  const double hmin = twoD ? std::min(h.x, h.y) : std::min({h.x, h.y, h.z});
  return rho * gamma0 / dt + 2.0 * (twoD ? 2.0 : 3.0) * mu / (hmin * hmin);
}

/// Calls visit(i, j, k, centre, phi) for every cell of this rank's box the body covers (phi > 0).
template <class Visit>
void forEachCoveredCell(const Body& b, const FaceBox& box, Visit&& visit) {
  const CartesianGrid& g = box.grid;
  Vec3 blo, bhi;
  bodyBounds(b, blo, bhi);
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    if (box.twoD && a == 2) {
      lo[a] = 0;
      hi[a] = g.cells[a] - 1;
      continue;
    }
    lo[a] = std::max(0, static_cast<int>(std::floor((blo[a] - g.origin[a]) / g.spacing[a])) - 1);
    hi[a] = std::min(g.cells[a] - 1, static_cast<int>(std::floor((bhi[a] - g.origin[a]) / g.spacing[a])) + 1);
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const Vec3 lower{g.origin.x + i * g.spacing.x, g.origin.y + j * g.spacing.y, g.origin.z + k * g.spacing.z};
        const double phi = coveredFraction(b, lower, lower + g.spacing);
        if (phi > 0.0) visit(i, j, k, lower + 0.5 * g.spacing, phi);
      }
}

/// Force and torque on the body of the implicit forcing after the step: the fluid's implicit drag
/// term at a face is (K_cc (u_b,cc - u_f) + K_cm (u_b,cm - u_f)) / 2 per volume (fluid/momentum_rhs.hpp:
/// K and K u_b averaged from the two cells beside the face); the body feels its opposite. Sums over
/// the faces of the cells the body covers, with this step's K of the body alone.
inline FaceSums implicitForcingLoad(const Body& b, const FaceBox& box, const std::array<const Field*, 3>& u,
                                    double diagonal) {
  FaceSums s;
  const CartesianGrid& g = box.grid;
  const double V = g.cellVolume();
  forEachCoveredCell(b, box, [&](int i, int j, int k, const Vec3& x, double phi) {
    const double K = penaltyCoefficient(phi, diagonal);
    const Vec3 ub = rigidVelocity(b, x);
    for (int c = 0; c < (box.twoD ? 2 : 3); ++c)
      for (int side = 0; side < 2; ++side) {
        int idx[3] = {i, j, k};
        idx[c] += side;  // the cell's lower (side 0) and upper (side 1) face of component c
        const int gNormal = box.offset[c] + idx[c];
        if (!box.periodic[c] && (gNormal == 0 || gNormal == box.global[c])) continue;  // boundary face
        Vec3 xf = x;
        xf[c] += (side - 0.5) * g.spacing[c];
        Vec3 f;  // on the body, N
        f[c] = 0.5 * K * ((*u[c])(idx[0], idx[1], idx[2]) - ub[c]) * V;
        s.force += f;
        s.torque += cross(xf - b.centre, f);
      }
  });
  return s;
}

/// The fluid momentum the implicit forcing holds to the body (per unit density) and its moment: each
/// face velocity weighted by w = K_f / (K_f + D), K_f = (K_cc + K_cm) / 2 its penalty (the face's tie
/// to the body in the predictor). A face beside a covered cell is held whole even where the body
/// covers half of it, so this exceeds sum phi u V by about half a cell layer: the rigid-body
/// correction must take what the penalty accelerates, or that excess acts as a lagged added mass.
inline FaceSums penaltyMomentumInside(const Body& b, const FaceBox& box, const std::array<const Field*, 3>& u,
                                      double diagonal) {
  FaceSums s;
  const CartesianGrid& g = box.grid;
  const double V = g.cellVolume();
  auto cellK = [&](const int (&cell)[3]) {
    if (!g.isInterior(cell[0], cell[1], cell[2])) return 0.0;
    const Vec3 lower{g.origin.x + cell[0] * g.spacing.x, g.origin.y + cell[1] * g.spacing.y,
                     g.origin.z + cell[2] * g.spacing.z};
    const double phi = coveredFraction(b, lower, lower + g.spacing);
    return phi > 0.0 ? penaltyCoefficient(phi, diagonal) : 0.0;
  };
  Vec3 blo, bhi;
  bodyBounds(b, blo, bhi);
  for (int c = 0; c < (box.twoD ? 2 : 3); ++c) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const int n = g.cells[a] + (a == c ? 1 : 0);
      if (box.twoD && a == 2) {
        lo[a] = 0;
        hi[a] = n - 1;
        continue;
      }
      lo[a] = std::max(0, static_cast<int>(std::floor((blo[a] - g.origin[a]) / g.spacing[a])) - 1);
      hi[a] = std::min(n - 1, static_cast<int>(std::floor((bhi[a] - g.origin[a]) / g.spacing[a])) + 2);
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const int above[3] = {i, j, k};
          if (above[c] >= g.cells[c]) continue;  // (the face shared with the next box: counted there)
          int below[3] = {i, j, k};
          below[c] -= 1;
          const double Kf = 0.5 * (cellK(above) + cellK(below));
          if (Kf <= 0.0) continue;
          const double w = Kf / (Kf + diagonal);
          Vec3 x;
          for (int a = 0; a < 3; ++a) x[a] = g.origin[a] + (above[a] + (a == c ? 0.0 : 0.5)) * g.spacing[a];
          Vec3 m;
          m[c] = w * (*u[c])(i, j, k) * V;
          s.momentum += m;
          s.angularMomentum += cross(x - b.centre, m);
        }
  }
  return s;
}

/// Imposes the body's rigid velocity on the predicted face velocities u (u-hat -> u-tilde) and
/// returns the force and torque of the forcing on the body (momentum fields zero).
inline FaceSums imposeRigidMotion(const Body& b, const FaceBox& box, Field (&u)[3], double rho, double gamma0, double dt) {
  FaceSums s;
  const double V = box.grid.cellVolume();
  forEachCoveredFace(b, box, [&](int c, int i, int j, int k, const Vec3& x, double phi, bool counted) {
    double& uf = u[c](i, j, k);
    const double du = phi * (rigidVelocity(b, x)[c] - uf);
    uf += du;
    if (!counted) return;
    Vec3 f;  // force density on the fluid, N/m^3 (seed eq. 2.9)
    f[c] = rho * gamma0 * du / dt;
    s.force -= f * V;
    s.torque -= cross(x - b.centre, f) * V;
  });
  return s;
}

/// The fluid's momentum inside the body (per unit density) and its moment about the centre.
inline FaceSums fluidMomentumInside(const Body& b, const FaceBox& box, const std::array<const Field*, 3>& u) {
  FaceSums s;
  const double V = box.grid.cellVolume();
  forEachCoveredFace(b, box, [&](int c, int i, int j, int k, const Vec3& x, double phi, bool counted) {
    if (!counted) return;
    Vec3 m;
    m[c] = phi * (*u[c])(i, j, k) * V;
    s.momentum += m;
    s.angularMomentum += cross(x - b.centre, m);
  });
  return s;
}

}  // namespace gf::resolved
