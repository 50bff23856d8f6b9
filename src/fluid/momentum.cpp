// Momentum predictor: convection (explicit, extrapolated), BDF2 time derivative, implicit
// viscous and drag terms solved with Jacobi-preconditioned BiCGStab per velocity component.
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/reduction.hpp"
#include "fluid/convection_varying.hpp"
#include "fluid/double2.hpp"
#include "fluid/loops.hpp"
#include "fluid/momentum_rhs.hpp"
#include "fluid/schemes.hpp"
#include "fluid/solver.hpp"
#include "fluid/staggered_eps.hpp"

namespace gf::fluid {

namespace {

/// N = div(rho eps u u_c) at the faces of component c (finite volume around the face; mass
/// fluxes interpolated to the control-volume faces, transported value central or van Leer).
///
/// Where eps varies (convectionVaryingKernel, fluid/convection_varying.hpp) the explicit rest of
/// the viscous stress of seed 000 eq. 5.6, div(eps mu [(grad u)^T - 2/3 (div u) I]), is
/// subtracted from N as well (it vanishes for constant eps and a divergence-free field, so the
/// eps = 1 path, convectionKernel, skips it).
/// div u per cell on the cells -1..n of every axis (one ghost layer: the periodic faces read it).
/// Lines [lineBegin, lineEnd) on the calling thread (lineEnd < 0: all lines, threaded); line =
/// (j + 1) + (ny + 2) (k + 1).
void cellDivergence(const Field u[3], Field& out, int dims, std::int64_t lineBegin, std::int64_t lineEnd) {
  const CartesianGrid& g = out.grid();
  const int ex = g.cells[0] + 2, ey = g.cells[1] + 2, ez = g.cells[2] + 2;
  double* D = out.data().data();
  const double invH[3] = {1.0 / g.spacing[0], 1.0 / g.spacing[1], 1.0 / g.spacing[2]};
  const double* U[3];
  std::ptrdiff_t su[3];
  for (int a = 0; a < dims; ++a) {
    U[a] = u[a].data().data();
    su[a] = u[a].stride(a);
  }
  forLines(static_cast<std::int64_t>(ey) * ez, lineBegin, lineEnd, [&](std::int64_t line) {
    const int j = static_cast<int>(line % ey) - 1, k = static_cast<int>(line / ey) - 1;
    const std::size_t d0 = out.index(-1, j, k);
    const double* L[3];  // point i = -1 of the line, per component
    for (int a = 0; a < dims; ++a) L[a] = U[a] + u[a].index(-1, j, k);
    for (int i = 0; i < ex; ++i) {  // cell i - 1
      double dv = 0.0;
      for (int a = 0; a < dims; ++a) dv += (L[a][i + su[a]] - L[a][i]) * invH[a];
      D[d0 + static_cast<std::size_t>(i)] = dv;
    }
  });
}

template <bool TVD, int DIMS>
void convectionKernel(const Field u[3], const Field& eps, const std::vector<std::uint8_t>& mask, Field& out, int c,
                      double rho, double /*mu*/, const Field& /*divergenceField*/, std::int64_t lineBegin,
                      std::int64_t lineEnd) {
  constexpr int dims = DIMS;  // compile-time: the direction loops unroll
  const Field& uc = u[c];
  const CartesianGrid& g = uc.grid();
  const auto& pts = uc.points();
  const double* U = uc.data().data();
  double* O = out.data().data();
  std::ptrdiff_t su[3];
  for (int d = 0; d < 3; ++d) su[d] = uc.stride(d);
  forLines(static_cast<std::int64_t>(pts[1]) * pts[2], lineBegin, lineEnd, [&](std::int64_t line) {
    const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
    const std::size_t f0 = uc.index(0, j, k);
    std::size_t d0[3];
    for (int d = 0; d < 3; ++d) d0[d] = u[d].index(0, j, k);
    // The x-direction flux F q through face i + 1/2 is point i's plus term and point i + 1's
    // minus term (the same expression): computed once per face into a line buffer, xFlux[i + 1]
    // for face i + 1/2 (i = -1 .. n-1).
    thread_local std::vector<double> xFluxBuffer;
    xFluxBuffer.resize(static_cast<std::size_t>(pts[0]) + 1);
    double* xFlux = xFluxBuffer.data();
    {
      const double* V = u[0].data().data();
      const std::ptrdiff_t vc = u[0].stride(c);
      for (int i = -1; i < pts[0]; ++i) {
        const std::size_t f = f0 + i;
        double Fp;
        if (c == 0) {
          Fp = rho * 1.0 * 0.5 * (U[f] + U[f + 1]);
        } else {
          const std::size_t idc = d0[0] + i, idm = idc - vc;
          Fp = rho * 1.0 * (0.5 * (V[idc + 1] + V[idm + 1]));
        }
        xFlux[i + 1] = Fp * faceValue<TVD>(Fp, U[f - 1], U[f], U[f + 1], U[f + 2]);
      }
    }
    auto point = [&](int i) {
      const std::size_t f = f0 + i;
      if (!mask[f]) {
        O[f] = 0.0;
        return;
      }
      double N = (xFlux[i + 1] - xFlux[i]) / g.spacing[0];
      for (int d = 1; d < dims; ++d) {
        double Fp, Fm;
        if (d == c) {
          Fp = rho * 1.0 * 0.5 * (U[f] + U[f + su[c]]);
          Fm = rho * 1.0 * 0.5 * (U[f - su[c]] + U[f]);
        } else {
          const double* V = u[d].data().data();
          const std::ptrdiff_t vc = u[d].stride(c), vd = u[d].stride(d);
          const std::size_t idc = d0[d] + i, idm = idc - vc;
          Fp = rho * 1.0 * (0.5 * (V[idc + vd] + V[idm + vd]));
          Fm = rho * 1.0 * (0.5 * (V[idc] + V[idm]));
        }
        const std::ptrdiff_t s = su[d];
        const double qp = faceValue<TVD>(Fp, U[f - s], U[f], U[f + s], U[f + 2 * s]);
        const double qm = faceValue<TVD>(Fm, U[f - 2 * s], U[f - s], U[f], U[f + s]);
        N += (Fp * qp - Fm * qm) / g.spacing[d];
      }
      O[f] = N;
    };
    int i = 0;
    if constexpr (!TVD) {
      // Central scheme: points 1 .. n - 2 of a line of unknowns there two at a time, each lane
      // with the arithmetic of point() (faceValue<false> is 0.5 (q0 + q1); fluid/double2.hpp):
      // the same bits.
      if (pts[0] >= 4 && std::memchr(mask.data() + f0 + 1, 0, static_cast<std::size_t>(pts[0] - 2)) == nullptr) {
        point(0);
        for (i = 1; i + 2 <= pts[0] - 1; i += 2) {
          const std::size_t f = f0 + i;
          Double2 N = (load2(xFlux + i + 1) - load2(xFlux + i)) / g.spacing[0];
          for (int d = 1; d < dims; ++d) {
            Double2 Fp, Fm;
            if (d == c) {
              Fp = rho * 1.0 * 0.5 * (load2(U + f) + load2(U + f + su[c]));
              Fm = rho * 1.0 * 0.5 * (load2(U + f - su[c]) + load2(U + f));
            } else {
              const double* V = u[d].data().data();
              const std::ptrdiff_t vc = u[d].stride(c), vd = u[d].stride(d);
              const std::size_t idc = d0[d] + i, idm = idc - vc;
              Fp = rho * 1.0 * (0.5 * (load2(V + idc + vd) + load2(V + idm + vd)));
              Fm = rho * 1.0 * (0.5 * (load2(V + idc) + load2(V + idm)));
            }
            const std::ptrdiff_t s = su[d];
            const Double2 qp = 0.5 * (load2(U + f) + load2(U + f + s));
            const Double2 qm = 0.5 * (load2(U + f - s) + load2(U + f));
            N += (Fp * qp - Fm * qm) / g.spacing[d];
          }
          store2(O + f, N);
        }
      }
    }
    for (; i < pts[0]; ++i) point(i);
  });
  (void)eps;
}

/// The eps-varying convection with shared face fluxes (fluid/convection_varying.hpp): lines
/// [lineBegin, lineEnd) on this thread, or (lineEnd < 0) all lines in one contiguous run per thread.
template <bool TVD, int DIMS>
void convectionVaryingKernel(const Field u[3], const Field& eps, const std::vector<std::uint8_t>& mask, Field& out,
                             int c, double rho, double mu, const Field& divergenceField, std::int64_t lineBegin,
                             std::int64_t lineEnd) {
  if (lineEnd >= 0) {
    VaryingConvection<TVD, DIMS>(u, eps, mask, out, c, rho, mu, divergenceField).run(lineBegin, lineEnd);
    return;
  }
  const auto& pts = u[c].points();
  const std::int64_t lines = static_cast<std::int64_t>(pts[1]) * pts[2];
  if (lines < kSerialBelow || serialLoops()) {
    VaryingConvection<TVD, DIMS>(u, eps, mask, out, c, rho, mu, divergenceField).run(0, lines);
    return;
  }
#pragma omp parallel
  {
    const std::int64_t t = omp_get_thread_num(), team = omp_get_num_threads();
    VaryingConvection<TVD, DIMS>(u, eps, mask, out, c, rho, mu, divergenceField)
        .run(lines * t / team, lines * (t + 1) / team);
  }
}

/// y = (rho gamma0 eps_f / dt + K_f) x - div(mu eps grad x) at the unknown faces of component c.
template <bool UNIFORM, int DIMS>
void helmholtzKernel(const Field& x, std::vector<double>& y, const std::vector<std::uint8_t>& mask, const Field& eps,
                     const Field& K, int c, double mu, double timeCoeff, bool jacobiDiagonal) {
  constexpr int dims = DIMS;  // compile-time: the direction loops unroll
  const CartesianGrid& g = x.grid();
  const auto& pts = x.points();
  const double* X = x.data().data();
  const double* E = eps.data().data();
  const double* Kd = K.data().data();
  double* Y = y.data();
  std::ptrdiff_t sx[3], se[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    sx[d] = x.stride(d);
    se[d] = eps.stride(d);
    w[d] = mu / (g.spacing[d] * g.spacing[d]);
  }
  if constexpr (UNIFORM) {
    if (!jacobiDiagonal) {
      // eps = 1, K = 0: constant-coefficient stencil written as one branch-free expression
      // per line (vectorises).
      const double diag = timeCoeff + 2.0 * (w[0] + w[1] + (dims == 3 ? w[2] : 0.0));
      const double wz = dims == 3 ? w[2] : 0.0;
      parallelFor(static_cast<std::int64_t>(pts[1]) * pts[2], [&](std::int64_t line) {
        const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
        const std::size_t f0 = x.index(0, j, k);
        const double* Xl = X + f0;
        double* Yl = Y + f0;
        const std::uint8_t* Ml = mask.data() + f0;
        const std::ptrdiff_t sy = sx[1], sz = sx[2];
        for (int i = 0; i < pts[0]; ++i) {
          const double v = diag * Xl[i] - w[0] * (Xl[i + 1] + Xl[i - 1]) - w[1] * (Xl[i + sy] + Xl[i - sy]) -
                           wz * (Xl[i + sz] + Xl[i - sz]);
          Yl[i] = Ml[i] ? v : Yl[i];
        }
      });
      return;
    }
  }
  parallelFor(static_cast<std::int64_t>(pts[1]) * pts[2], [&](std::int64_t line) {
    const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
    const std::size_t f0 = x.index(0, j, k), e0 = eps.index(0, j, k);
    for (int i = 0; i < pts[0]; ++i) {
      const std::size_t f = f0 + i;
      if (!mask[f]) continue;
      const std::size_t cc = e0 + i, cm = cc - se[c];
      double diag = timeCoeff;
      if constexpr (!UNIFORM) diag = timeCoeff * 0.5 * (E[cc] + E[cm]) + 0.5 * (Kd[cc] + Kd[cm]);
      double off = 0.0;
      for (int d = 0; d < dims; ++d) {
        double ep = 1.0, em = 1.0;
        if constexpr (!UNIFORM) {
          const FaceVoidFractions face = controlVolumeFaceEps(E, cc, cm, se[d], d == c);
          ep = face.plus;
          em = face.minus;
        }
        diag += w[d] * (ep + em);
        off += w[d] * (ep * X[f + sx[d]] + em * X[f - sx[d]]);
      }
      Y[f] = jacobiDiagonal ? diag : diag * X[f] - off;
    }
  });
}

/// helmholtzKernel for a run-time dimension count.
template <bool UNIFORM>
void helmholtzKernel(const Field& x, std::vector<double>& y, const std::vector<std::uint8_t>& mask, const Field& eps,
                     const Field& K, int c, double mu, double timeCoeff, int dims, bool jacobiDiagonal) {
  if (dims == 3) helmholtzKernel<UNIFORM, 3>(x, y, mask, eps, K, c, mu, timeCoeff, jacobiDiagonal);
  else helmholtzKernel<UNIFORM, 2>(x, y, mask, eps, K, c, mu, timeCoeff, jacobiDiagonal);
}

/// Jacobi diagonal of the eps = 1, K = 0 operator, in the arithmetic order of the stored diagonal
/// of solveHelmholtz (generic helmholtzKernel, then the no-slip closure rows): base, then 2 w_d
/// for each tangential direction d whose min / max side is a wall or inlet, on the row next to it.
struct UniformJacobiDiagonal {
  double base = 0.0;
  double add[3] = {0.0, 0.0, 0.0};
  bool lo[3] = {false, false, false}, hi[3] = {false, false, false};
  int n[3] = {1, 1, 1};
  double value(int i, int j, int k) const {
    const int idx[3] = {i, j, k};
    double v = base;
    for (int d = 0; d < 3; ++d) {
      if (lo[d] && idx[d] == 0) v += add[d];
      if (hi[d] && idx[d] == n[d] - 1) v += add[d];
    }
    return v;
  }
};

/// One Chebyshev-accelerated Jacobi sweep for eps = 1, K = 0 fused with the residual:
///   y <- y + omega (x + D^-1 (b - A x) - y)   at the unknown faces (y = x elsewhere),
/// where y holds the previous iterate x_{k-1} on entry (omega = 1: plain Jacobi). Returns
/// |b - A x|^2 summed line by line in line order (deterministic). x must have its ghosts filled.
double jacobiSweepUniform(const Field& x, Field& y, const double* B, const UniformJacobiDiagonal& jd,
                          const std::vector<std::uint8_t>& mask, double mu, double timeCoeff, int dims,
                          double omega, std::vector<double>& linePartial) {
  const CartesianGrid& g = x.grid();
  const auto& pts = x.points();
  double w[3];
  for (int d = 0; d < 3; ++d) w[d] = mu / (g.spacing[d] * g.spacing[d]);
  const double wz = dims == 3 ? w[2] : 0.0;
  const double diag = timeCoeff + 2.0 * (w[0] + w[1] + wz);
  const std::ptrdiff_t sy = x.stride(1), sz = x.stride(2);
  const std::int64_t lines = static_cast<std::int64_t>(pts[1]) * pts[2];
  const bool plainJacobi = omega == 1.0;
  linePartial.resize(static_cast<std::size_t>(lines));
  const double* X = x.data().data();
  double* Y = y.data().data();
  parallelFor(lines, [&](std::int64_t line) {
    const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
    const std::size_t f0 = x.index(0, j, k);
    const double* Xl = X + f0;
    double* Yl = Y + f0;
    const double* Bl = B + f0;
    const std::uint8_t* Ml = mask.data() + f0;
    // 1 / Jacobi diagonal: one value inside the line, others at its two ends (no array read).
    const int last = pts[0] - 1;
    const double inv0 = 1.0 / jd.value(0, j, k), invLast = 1.0 / jd.value(last, j, k);
    const double invMid = pts[0] > 2 ? 1.0 / jd.value(1, j, k) : inv0;
    double acc0 = 0.0, acc1 = 0.0;
    int i = 0;
    auto body = [&](int q, double& acc) {
      const double ax = diag * Xl[q] - w[0] * (Xl[q + 1] + Xl[q - 1]) - w[1] * (Xl[q + sy] + Xl[q - sy]) -
                        wz * (Xl[q + sz] + Xl[q - sz]);
      const double r = Ml[q] ? Bl[q] - ax : 0.0;
      const double invD = q == 0 ? inv0 : (q == last ? invLast : invMid);
      const double jacobi = Xl[q] + r * invD;
      // omega = 1 (first sweep): y's old content must not enter even by rounding (restart ==
      // continuous run, bit for bit).
      const double next = plainJacobi ? jacobi : Yl[q] + omega * (jacobi - Yl[q]);
      Yl[q] = Ml[q] ? next : Xl[q];
      acc += r * r;
    };
    // Points 2 .. last - 1 of a line with no zero mask byte there (std::memchr): two at a time in
    // the lanes of a two-double vector, lane 0 the even points (acc0), lane 1 the odd ones (acc1),
    // each lane with the arithmetic of body(): the same bits, in about two thirds of the time
    // (GCC does not vectorise body() itself: its selects and end cases).
    if (pts[0] >= 4 && std::memchr(Ml + 2, 0, static_cast<std::size_t>(last - 2)) == nullptr) {
      body(0, acc0);
      body(1, acc1);
      Double2 acc{acc0, acc1};
      for (i = 2; i + 2 <= last; i += 2) {
        const Double2 xq = load2(Xl + i);
        const Double2 ax = diag * xq - w[0] * (load2(Xl + i + 1) + load2(Xl + i - 1)) -
                           w[1] * (load2(Xl + i + sy) + load2(Xl + i - sy)) -
                           wz * (load2(Xl + i + sz) + load2(Xl + i - sz));
        const Double2 r = load2(Bl + i) - ax;
        const Double2 jacobi = xq + r * invMid;
        if (plainJacobi) {
          store2(Yl + i, jacobi);
        } else {
          const Double2 yq = load2(Yl + i);
          store2(Yl + i, yq + omega * (jacobi - yq));
        }
        acc += r * r;
      }
      acc0 = acc[0];
      acc1 = acc[1];
    }
    for (; i + 2 <= pts[0]; i += 2) {
      body(i, acc0);
      body(i + 1, acc1);
    }
    for (; i < pts[0]; ++i) body(i, acc0);
    linePartial[static_cast<std::size_t>(line)] = acc0 + acc1;
  });
  return sumOfPartials(linePartial);
}

}  // namespace

void Solver::computeCellDivergence(const PlaneSlab* slab) {
  const int dims = twoD_ ? 2 : 3;
  if (!slab) {
    if (cellDivergence_.data().size() != p_.data().size()) cellDivergence_ = Field(grid_);
    cellDivergence(u_, cellDivergence_, dims, 0, -1);
    return;
  }
  // Cells -1..n along y and z: line (j + 1) + (ny + 2)(k + 1); the first and last members also
  // take the ghost planes k = -1 and k = nz.
  const std::int64_t ey = grid_.cells[1] + 2;
  const std::int64_t b = (slab->first ? 0 : slab->k0 + 1) * ey;
  const std::int64_t e = (slab->last ? grid_.cells[2] + 2 : slab->k1 + 1) * ey;
  cellDivergence(u_, cellDivergence_, dims, b, e);
}

void Solver::computeConvection(Field out[3], const PlaneSlab* slab, double rho, double mu) {
  const int dims = twoD_ ? 2 : 3;
  const double rhoK = rho >= 0.0 ? rho : rho_, muK = mu >= 0.0 ? mu : mu_;
  if (!uniformCoupling_ && !slab) computeCellDivergence(nullptr);
  const bool tvd = scheme_ == ConvectionScheme::VanLeer;
  auto run = [&](auto kernel) {
    for (int c = 0; c < dims; ++c) {
      const auto& pts = u_[c].points();
      kernel(u_, coupling_.voidFraction, unknown_[c], out[c], c, rhoK, muK, cellDivergence_,
             slab ? slab->lineBegin(pts) : 0, slab ? slab->lineEnd(pts) : -1);
    }
  };
  auto byDims = [&](auto tvdC, auto uniformC) {
    constexpr bool T = decltype(tvdC)::value, U = decltype(uniformC)::value;
    if constexpr (U) {
      if (dims == 3) run(convectionKernel<T, 3>);
      else run(convectionKernel<T, 2>);
    } else {
      if (dims == 3) run(convectionVaryingKernel<T, 3>);
      else run(convectionVaryingKernel<T, 2>);
    }
  };
  if (tvd && uniformCoupling_) byDims(std::true_type{}, std::true_type{});
  else if (tvd) byDims(std::true_type{}, std::false_type{});
  else if (uniformCoupling_) byDims(std::false_type{}, std::true_type{});
  else byDims(std::false_type{}, std::false_type{});
}

MomentumRhsPoint Solver::momentumRhsPoint(int c, double dt, double g1, double g2, double e1, double e2) const {
  MomentumRhsPoint r;
  r.U = u_[c].data().data();
  r.Uo = uOld_[c].data().data();
  r.No = convOld_[c].data().data();
  r.P = p_.data().data();
  r.E = coupling_.voidFraction.data().data();
  r.En = coupling_.voidFractionOld.data().data();
  r.Enm = epsOlder_.data().data();
  r.F = coupling_.forceDensity[c].data().data();
  r.K = coupling_.dragCoefficient.data().data();
  r.Up = coupling_.particleVelocity[c].data().data();
  r.se = p_.stride(c);
  r.invH = 1.0 / grid_.spacing[c];
  r.rdt = rho_ / dt;
  r.g1 = g1;
  r.g2 = g2;
  r.e1 = e1;
  r.e2 = e2;
  r.rho = rho_;
  r.gc = gravity_[c];
  r.drive = (driveMode_ != DrivingMode::None && driveAxis_ == c) ? drive_ : 0.0;
  r.modelA = model_ == MomentumModel::A;
  return r;
}

void Solver::assembleMomentum(int c, double dt, double g0, double g1, double g2, double e1, double e2,
                              std::int64_t lineBegin, std::int64_t lineEnd) {
  const Field& uc = u_[c];
  const auto& pts = uc.points();
  const double* U = uc.data().data();
  const double* Uo = uOld_[c].data().data();
  const double* N = conv_[c].data().data();
  const double* No = convOld_[c].data().data();
  const double* P = p_.data().data();
  const double* F = coupling_.forceDensity[c].data().data();
  double* R = rhs_[c].data().data();
  const auto& mask = unknown_[c];
  const std::ptrdiff_t se = p_.stride(c);
  const double invH = 1.0 / grid_.spacing[c];
  const double rdt = rho_ / dt;
  const double gc = gravity_[c];
  const double drive = (driveMode_ != DrivingMode::None && driveAxis_ == c) ? drive_ : 0.0;
  if (uniformCoupling_) {
    // eps = eps_old = eps_older = 1 and K = 0 (ghosts included): the general expression below with
    // those values (same arithmetic; the drag term K u_p is an exact zero), without reading them.
    // |b|^2 per grid line as well (all lines: solveHelmholtz's ||b|| without another pass).
    const std::int64_t lines = static_cast<std::int64_t>(pts[1]) * pts[2];
    const bool norm = lineEnd < 0;
    if (norm) linePartial_.resize(static_cast<std::size_t>(lines));
    forLines(lines, lineBegin, lineEnd, [&](std::int64_t line) {
      const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
      const std::size_t f0 = uc.index(0, j, k), e0 = p_.index(0, j, k);
      double bb = 0.0;
      auto point = [&](int i) {
        const std::size_t f = f0 + i;
        if (!mask[f]) return;
        const std::size_t cc = e0 + i, cm = cc - se;
        double r = rdt * (g1 * U[f] - g2 * Uo[f]);
        r -= e1 * N[f] - e2 * No[f];
        r -= (P[cc] - P[cm]) * invH;
        r += rho_ * gc + drive;
        r += 0.5 * (F[cc] + F[cm]) + 0.0;
        R[f] = r;
        bb += r * r;
      };
      int i = 0;
      // Points 1 .. n - 2 of a line of unknowns there: two at a time, each lane with the
      // arithmetic of point() (fluid/double2.hpp): the same bits.
      if (pts[0] >= 4 && std::memchr(mask.data() + f0 + 1, 0, static_cast<std::size_t>(pts[0] - 2)) == nullptr) {
        point(0);
        const double body = rho_ * gc + drive;
        for (i = 1; i + 2 <= pts[0] - 1; i += 2) {
          const std::size_t f = f0 + i, cc = e0 + i, cm = cc - se;
          Double2 r = rdt * (g1 * load2(U + f) - g2 * load2(Uo + f));
          r -= e1 * load2(N + f) - e2 * load2(No + f);
          r -= (load2(P + cc) - load2(P + cm)) * invH;
          r += body;
          r += 0.5 * (load2(F + cc) + load2(F + cm)) + 0.0;
          store2(R + f, r);
          const Double2 rr = r * r;
          bb += rr[0];
          bb += rr[1];
        }
      }
      for (; i < pts[0]; ++i) point(i);
      if (norm) linePartial_[static_cast<std::size_t>(line)] = bb;
    });
    rhsNorm2Kept_[c] = norm;
    if (norm) rhsNorm2_[c] = sumOfPartials(linePartial_);
    return;
  }
  const MomentumRhsPoint rhs = momentumRhsPoint(c, dt, g1, g2, e1, e2);
  forLines(static_cast<std::int64_t>(pts[1]) * pts[2], lineBegin, lineEnd, [&](std::int64_t line) {
    const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
    const std::size_t f0 = uc.index(0, j, k), e0 = p_.index(0, j, k);
    for (int i = 0; i < pts[0]; ++i) {
      const std::size_t f = f0 + i;
      if (!mask[f]) continue;
      R[f] = rhs(f, e0 + i, N[f]);
    }
  });
  (void)g0;
}

void Solver::applyHelmholtz(int c, const Field& x, std::vector<double>& y, double dt, double g0) const {
  const int dims = twoD_ ? 2 : 3;
  const double timeCoeff = rho_ * g0 / dt;
  if (uniformCoupling_)
    helmholtzKernel<true>(x, y, unknown_[c], coupling_.voidFraction, coupling_.dragCoefficient, c, mu_, timeCoeff,
                          dims, false);
  else
    helmholtzKernel<false>(x, y, unknown_[c], coupling_.voidFraction, coupling_.dragCoefficient, c, mu_, timeCoeff,
                           dims, false);
}

int Solver::solveHelmholtz(int c, double dt, double g0, bool predictor) {
  // Jacobi-preconditioned BiCGStab (van der Vorst 1992) on the correction of u_c. The vectors
  // span the whole flat array (ghosts included) and are zero off the unknown faces, so every
  // vector operation is one contiguous loop.
  // (no unknowns on any rank: a rank without any takes part in the others' reductions)
  if (!anyUnknowns_[c]) {
    if (predictor) uOld_[c].data() = u_[c].data();
    return 0;
  }
  Field& x = u_[c];
  const auto n = static_cast<std::int64_t>(x.data().size());
  double* X = x.data().data();
  const double* B = rhs_[c].data().data();
  double* r = krylov_[0].data();
  double* rhat = krylov_[1].data();
  double* p = krylov_[2].data();
  double* v = krylov_[3].data();
  double* s = krylov_[4].data();
  double* t = krylov_[5].data();
  double* invDiag = krylov_[6].data();
  Field& y = precY_[c];
  Field& z = precZ_[c];
  double* Y = y.data().data();
  double* Z = z.data().data();
  const auto& mask = unknown_[c];
  const int dims = twoD_ ? 2 : 3;
  // Jacobi diagonal (inverted) for the Jacobi and BiCGStab paths; the Chebyshev sweeps compute it
  // on the fly (UniformJacobiDiagonal) and build the array only if they stall.
  auto buildInverseDiagonal = [&]() {
    if (uniformCoupling_)
      helmholtzKernel<true>(x, krylov_[6], mask, coupling_.voidFraction, coupling_.dragCoefficient, c, mu_,
                            rho_ * g0 / dt, dims, true);
    else
      helmholtzKernel<false>(x, krylov_[6], mask, coupling_.voidFraction, coupling_.dragCoefficient, c, mu_,
                             rho_ * g0 / dt, dims, true);
    // The quadratic no-slip closure u_g = (8 u_w - 6 u_0 + u_1)/3 adds 2 w eps to the diagonal
    // of the rows next to walls and inlets (tangential directions): exact Jacobi diagonal.
    for (int d = 0; d < dims; ++d) {
      if (d == c) continue;
      const double wd = mu_ / (grid_.spacing[d] * grid_.spacing[d]);
      const auto& pts = x.points();
      for (int side = 0; side < 2; ++side) {
        const BoundaryType type = bc_.at(d, side).type;
        if (type != BoundaryType::Wall && type != BoundaryType::Inlet) continue;
        const int row = side == 0 ? 0 : grid_.cells[d] - 1;
        const int b1 = (d + 1) % 3, b2 = (d + 2) % 3;
        for (int q = 0; q < pts[b2]; ++q)
          for (int pp = 0; pp < pts[b1]; ++pp) {
            int idx[3];
            idx[d] = row;
            idx[b1] = pp;
            idx[b2] = q;
            const std::size_t f = x.index(idx[0], idx[1], idx[2]);
            if (!mask[f]) continue;
            const std::size_t cc = coupling_.voidFraction.index(idx[0], idx[1], idx[2]);
            const double* E = coupling_.voidFraction.data().data();
            const double epsF = uniformCoupling_ ? 1.0 : 0.5 * (E[cc] + E[cc - coupling_.voidFraction.stride(c)]);
            invDiag[f] += 2.0 * wd * epsF;
          }
      }
    }
    parallelForElements(n, [&](std::int64_t q) { invDiag[q] = mask[q] ? 1.0 / invDiag[q] : 0.0; });
  };
  UniformJacobiDiagonal jacobiDiagonal;
  {
    jacobiDiagonal.base = rho_ * g0 / dt;
    for (int d = 0; d < dims; ++d) {
      const double wd = mu_ / (grid_.spacing[d] * grid_.spacing[d]);
      jacobiDiagonal.base += wd * (1.0 + 1.0);  // helmholtzKernel: diag += w_d (eps_+ + eps_-)
      jacobiDiagonal.n[d] = grid_.cells[d];
      if (d == c) continue;
      jacobiDiagonal.add[d] = 2.0 * wd * 1.0;
      for (int side = 0; side < 2; ++side) {
        const BoundaryType type = bc_.at(d, side).type;
        (side == 0 ? jacobiDiagonal.lo : jacobiDiagonal.hi)[d] = type == BoundaryType::Wall || type == BoundaryType::Inlet;
      }
    }
  }
  // Initial guess: u^n extrapolated in time, 2 u^n - u^{n-1} (second order), plus the error of
  // that extrapolation in the previous step, e = u*^n - (2 u^{n-1} - u^{n-2}): the error is
  // dt^2 d2u/dt2 + O(dt^3) and changes slowly, so the corrected guess is third-order accurate in
  // time and the solve starts from a residual about 10x smaller (3 fewer sweeps per component on
  // the 64^3 cavity). guessError_ holds 2 u^n - u^{n-1} until the solve is done.
  double* Uo = uOld_[c].data().data();
  double* G = guessError_[c].data().data();
  // (Corrector solves start from the current velocity and leave u^{n-1} alone.)
  if (predictor) parallelForElements(n, [&](std::int64_t q) {
    const double un = X[q];
    if (mask[q]) {
      const double extrapolated = 2.0 * un - Uo[q];
      X[q] = extrapolated + G[q];
      G[q] = extrapolated;
    }
    Uo[q] = un;  // u^{n-1} <- u^n for the next step
  });
  fillVelocityGhosts(x, c, bc_, GhostMode::Full);
  // (||b||^2 from assembleMomentum where it has just computed b: eps = 1, predictor)
  const double bnorm = std::sqrt(predictor && rhsNorm2Kept_[c]
                                     ? rhsNorm2_[c]
                                     : globalSum(n, elementSums(), [&](std::int64_t q) { return mask[q] ? B[q] * B[q] : 0.0; }));
  rhsNorm2Kept_[c] = false;
  const double tol = momentumTolerance_ * (bnorm > 0.0 ? bnorm : 1.0);
  int it = 0;
  // Strongly diagonally dominant systems (small mu dt / h^2): plain Jacobi sweeps are much
  // cheaper than BiCGStab iterations; BiCGStab takes over if they stall.
  double offRatio = 0.0;
  for (int d = 0; d < dims; ++d) offRatio += 2.0 * mu_ / (grid_.spacing[d] * grid_.spacing[d]);
  offRatio /= rho_ * g0 / dt + offRatio;
  const bool chebyshev = offRatio < 0.6 && uniformCoupling_;
  if (!chebyshev) buildInverseDiagonal();
  // Residual and BiCGStab vectors (the Chebyshev sweeps compute their own residual).
  auto initialiseKrylov = [&]() {
    applyHelmholtz(c, x, krylov_[5], dt, g0);
    return std::sqrt(globalSum(n, elementSums(), [&](std::int64_t q) {
      r[q] = mask[q] ? B[q] - t[q] : 0.0;
      rhat[q] = r[q];
      p[q] = 0.0;
      v[q] = 0.0;
      t[q] = 0.0;
      s[q] = 0.0;
      return r[q] * r[q];
    }));
  };
  double rnorm = chebyshev ? std::numeric_limits<double>::infinity() : initialiseKrylov();
  if (chebyshev) {
    // eps = 1, K = 0: fused sweep (one pass + ghost fill per sweep), ping-pong with y, with
    // Chebyshev acceleration (Golub and Varga 1961; Saad, Iterative Methods 2003, sec. 12.3): the
    // Jacobi iteration matrix I - D^-1 A has real eigenvalues in [-offRatio, offRatio]
    // (Gershgorin; the wall closure rows are more diagonally dominant), so
    //   omega_1 = 1, omega_2 = 2 / (2 - rho^2), omega_{k+1} = 1 / (1 - rho^2 omega_k / 4)
    // gives the error reduction (1 - sqrt(1 - rho^2)) / rho per sweep instead of rho (0.31
    // instead of 0.56 for the 64^3 cavity: half the sweeps).
    const int maxSweeps = 40;
    const double rho2 = offRatio * offRatio;
    double omega = 1.0;
    while (rnorm > tol && it < maxSweeps) {
      ++it;
      omega = it == 1 ? 1.0 : (it == 2 ? 2.0 / (2.0 - rho2) : 1.0 / (1.0 - 0.25 * rho2 * omega));
      rnorm = std::sqrt(jacobiSweepUniform(x, y, B, jacobiDiagonal, mask, mu_, rho_ * g0 / dt, dims, omega, linePartial_));
      x.data().swap(y.data());
      fillVelocityStencilGhosts(x, c, bc_);  // only what the next sweep reads (full fill below)
    }
    X = x.data().data();
    Y = y.data().data();
    if (rnorm > tol) {  // stalled: BiCGStab from the current iterate
      buildInverseDiagonal();
      fillVelocityGhosts(x, c, bc_, GhostMode::Full);
      rnorm = initialiseKrylov();
    }
  } else if (offRatio < 0.6) {
    const int maxSweeps = 40;
    while (rnorm > tol && it < maxSweeps) {
      ++it;
      parallelForElements(n, [&](std::int64_t q) { X[q] += r[q] * invDiag[q]; });
      fillVelocityGhosts(x, c, bc_, GhostMode::Full);
      applyHelmholtz(c, x, krylov_[5], dt, g0);
      const double rr = globalSum2(n, elementSums(), [&](std::int64_t q, double& a, double&) {
                          r[q] = mask[q] ? B[q] - t[q] : 0.0;
                          a += r[q] * r[q];
                        }).first;
      rnorm = std::sqrt(rr);
    }
    if (rnorm > tol)
      parallelForElements(n, [&](std::int64_t q) {
        rhat[q] = r[q];
        t[q] = 0.0;
      });
  }
  double rhoNew = rnorm * rnorm;  // rhat = r at the start of BiCGStab
  double rho = 1.0, alpha = 1.0, omega = 1.0;
  while (rnorm > tol && it < momentumMaxIterations_) {
    ++it;
    if (rhoNew == 0.0) break;
    const double beta = (rhoNew / rho) * (alpha / omega);
    rho = rhoNew;
    parallelForElements(n, [&](std::int64_t q) {
      p[q] = r[q] + beta * (p[q] - omega * v[q]);
      Y[q] = p[q] * invDiag[q];
    });
    fillVelocityGhosts(y, c, bc_, GhostMode::Homogeneous);
    applyHelmholtz(c, y, krylov_[3], dt, g0);
    alpha = rho / gf::dot(rhat, v, n, elementSums());
    const double ss = globalSum2(n, elementSums(), [&](std::int64_t q, double& a, double&) {
                        s[q] = r[q] - alpha * v[q];
                        Z[q] = s[q] * invDiag[q];
                        a += s[q] * s[q];
                      }).first;
    if (std::sqrt(ss) <= tol) {
      parallelForElements(n, [&](std::int64_t q) { X[q] += alpha * Y[q]; });
      break;
    }
    fillVelocityGhosts(z, c, bc_, GhostMode::Homogeneous);
    applyHelmholtz(c, z, krylov_[5], dt, g0);
    const auto [tt, ts] = globalSum2(n, elementSums(), [&](std::int64_t q, double& a, double& b) {
      a += t[q] * t[q];
      b += t[q] * s[q];
    });
    omega = tt > 0.0 ? ts / tt : 0.0;
    const auto [rr, rhr] = globalSum2(n, elementSums(), [&](std::int64_t q, double& a, double& b) {
      X[q] += alpha * Y[q] + omega * Z[q];
      r[q] = s[q] - omega * t[q];
      a += r[q] * r[q];
      b += rhat[q] * r[q];
    });
    rnorm = std::sqrt(rr);
    rhoNew = rhr;
    if (omega == 0.0) break;
  }
  fillVelocityGhosts(x, c, bc_, GhostMode::Full);
  if (predictor) {
    X = x.data().data();
    parallelForElements(n, [&](std::int64_t q) { G[q] = mask[q] ? X[q] - G[q] : 0.0; });
  }
  return it;
}

}  // namespace gf::fluid

namespace gf::fluid {

double Solver::correctMomentum(double dt, double g0) {
  // PISO-style corrector (Issa 1986): the projection corrects the velocity with the time and drag
  // diagonal only, so u^{n+1} misses the implicit viscous operator applied to the correction. With
  // the new pressure in the right-hand side, b <- b - a grad(phi), the momentum residual
  // r = b - A u is that splitting error; the momentum equation is solved again with the new
  // pressure (from the current velocity) and projected again by the caller. Returns ||r|| / ||b||
  // before the solve.
  const int dims = twoD_ ? 2 : 3;
  const double* E = coupling_.voidFraction.data().data();
  const double* Phi = phi_.data().data();
  const bool modelA = model_ == MomentumModel::A;
  double rr = 0.0, bb = 0.0;
  for (int c = 0; c < dims; ++c) {
    Field& u = u_[c];
    double* R = rhs_[c].data().data();
    const double* Au = krylov_[5].data();
    const auto& mask = unknown_[c];
    const auto& pts = u.points();
    const std::ptrdiff_t se = p_.stride(c);
    const double invH = 1.0 / grid_.spacing[c];
    const auto lines = static_cast<std::int64_t>(pts[1]) * pts[2];
    auto forLine = [&](std::int64_t line, auto&& body) {
      const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
      const std::size_t f0 = u.index(0, j, k), e0 = p_.index(0, j, k);
      for (int i = 0; i < pts[0]; ++i)
        if (mask[f0 + i]) body(f0 + i, e0 + i, e0 + i - se);
    };
    parallelFor(lines, [&](std::int64_t line) {
      forLine(line, [&](std::size_t f, std::size_t cc, std::size_t cm) {
        const double a = modelA ? 0.5 * (E[cc] + E[cm]) : 1.0;
        R[f] -= a * (Phi[cc] - Phi[cm]) * invH;
      });
    });
    applyHelmholtz(c, u, krylov_[5], dt, g0);
    bb += globalSum(lines, lineSums(), [&](std::int64_t line) {
      double s = 0.0;
      forLine(line, [&](std::size_t f, std::size_t, std::size_t) { s += R[f] * R[f]; });
      return s;
    });
    rr += globalSum(lines, lineSums(), [&](std::int64_t line) {
      double s = 0.0;
      forLine(line, [&](std::size_t f, std::size_t, std::size_t) { s += (R[f] - Au[f]) * (R[f] - Au[f]); });
      return s;
    });
    stats_.momentumIterations += solveHelmholtz(c, dt, g0, false);
  }
  return bb > 0.0 ? std::sqrt(rr / bb) : 0.0;
}

/// Epilogue of the fused convection pass of a team member (predictMomentumTeam): b at every unknown
/// point right after its convection N^n (as assembleMomentum), and |b|^2 per grid line (the sum of
/// the team's initial-residual norm, in line order).
struct AssembleEpilogue {
  MomentumRhsPoint rhs;
  double* R;
  double* partial;
  double acc = 0.0;
  [[gnu::always_inline]] void point(std::size_t f, std::size_t cc, double Nf) {
    const double r = rhs(f, cc, Nf);
    R[f] = r;
    acc += r * r;
  }
  [[gnu::always_inline]] void line(std::int64_t line) {
    partial[line] = acc;
    acc = 0.0;
  }
};

void Solver::convectAndAssemble(const PlaneSlab& slab, double dt, double g1, double g2, double e1, double e2,
                                double* const partial[3]) {
  const bool tvd = scheme_ == ConvectionScheme::VanLeer;
  for (int c = 0; c < 3; ++c) {
    const auto& pts = u_[c].points();
    AssembleEpilogue after{momentumRhsPoint(c, dt, g1, g2, e1, e2), rhs_[c].data().data(), partial[c]};
    if (tvd)
      VaryingConvection<true, 3>(u_, coupling_.voidFraction, unknown_[c], conv_[c], c, rho_, mu_, cellDivergence_)
          .run(slab.lineBegin(pts), slab.lineEnd(pts), after);
    else
      VaryingConvection<false, 3>(u_, coupling_.voidFraction, unknown_[c], conv_[c], c, rho_, mu_, cellDivergence_)
          .run(slab.lineBegin(pts), slab.lineEnd(pts), after);
  }
}

}  // namespace gf::fluid
