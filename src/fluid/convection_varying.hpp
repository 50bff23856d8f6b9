#pragma once
// Convection (and the explicit viscous-stress rest) of one velocity component where eps varies:
// the finite-volume form of convectionKernel<TVD, false, DIMS> (momentum.cpp) written with face
// fluxes. Each control-volume face is shared by two neighbouring points (the plus face of point
// f along d is the minus face of point f + e_d); its convective flux F q and stress flux are
// computed once, by one function of the lower point, and carried to the next point (along x),
// the next grid line (y) or the next plane (z) within a run of consecutive lines. A face whose
// lower point was not computed in the run is evaluated by the same function, so the result does
// not depend on how the lines are split between threads.
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "fluid/schemes.hpp"

namespace gf::fluid {

template <bool TVD, int DIMS>
class VaryingConvection {
 public:
  VaryingConvection(const Field u[3], const Field& eps, const std::vector<std::uint8_t>& mask, Field& out, int c,
                    double rho, double mu, const Field& divergence)
      : u_(u), eps_(eps), mask_(mask), out_(out), c_(c), rho_(rho), mu_(mu), div_(divergence) {
    const CartesianGrid& g = u[c].grid();
    for (int d = 0; d < 3; ++d) {
      su_[d] = u[c].stride(d);
      se_[d] = eps.stride(d);
      invH_[d] = 1.0 / g.spacing[d];
      V_[d] = u[d].data().data();
      vc_[d] = u[d].stride(c);
      vd_[d] = u[d].stride(d);
    }
  }

  /// Grid lines [lb, le) of the component (line = j + points[1] k), in order, on this thread.
  void run(std::int64_t lb, std::int64_t le) {
    const Field& uc = u_[c_];
    const auto& pts = uc.points();
    const int nx = pts[0], ny = pts[1];
    yCarry_.assign(static_cast<std::size_t>(nx), Flux{});
    zCarry_.assign(static_cast<std::size_t>(nx) * ny, Flux{});
    double* O = out_.data().data();
    for (std::int64_t line = lb; line < le; ++line) {
      const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
      const bool yRun = j > 0 && line - 1 >= lb;    // line (j - 1, k) was just done
      const bool zRun = line - ny >= lb;            // line (j, k - 1) was done in this run
      const std::size_t f0 = uc.index(0, j, k), e0 = eps_.index(0, j, k);
      std::size_t v0[3];
      for (int d = 0; d < 3; ++d) v0[d] = u_[d].index(0, j, k);
      Flux xCarry;
      for (int i = 0; i < nx; ++i) {
        Flux& yc = yCarry_[static_cast<std::size_t>(i)];
        Flux& zc = zCarry_[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j];
        if (!yRun) yc.valid = false;
        if (!zRun) zc.valid = false;
        const std::size_t f = f0 + i;
        if (!mask_[f]) {
          O[f] = 0.0;
          xCarry.valid = yc.valid = zc.valid = false;
          continue;
        }
        const std::size_t cc = e0 + i;
        std::size_t vi[3];
        for (int d = 0; d < 3; ++d) vi[d] = v0[d] + i;
        Flux* carry[3] = {&xCarry, &yc, &zc};
        double N = 0.0, stress[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < DIMS; ++d) {
          // Scalars, not Flux copies: a 16-byte copy of two separately stored doubles stalls on
          // store forwarding (40 % of this loop in perf).
          double minusConv, minusStress, plusConv, plusStress;
          if (carry[d]->valid) {
            minusConv = carry[d]->convective;
            minusStress = carry[d]->stress;
          } else {
            plusFlux(d, f - su_[d], cc - se_[d], vi[d] - vd_[d], minusConv, minusStress);
          }
          plusFlux(d, f, cc, vi[d], plusConv, plusStress);
          N += (plusConv - minusConv) * invH_[d];
          stress[d] = (plusStress - minusStress) * invH_[d];
          carry[d]->convective = plusConv;
          carry[d]->stress = plusStress;
          carry[d]->valid = true;
        }
        // div(eps mu [(grad u)^T - 2/3 (div u) I]) for component c: the c term, then the others.
        double T = stress[c_];
        for (int d = 0; d < DIMS; ++d)
          if (d != c_) T += stress[d];
        O[f] = N - mu_ * T;
      }
    }
  }

 private:
  struct Flux {
    double convective = 0.0, stress = 0.0;
    bool valid = false;
  };

  /// Fluxes through the plus face along d of the control volume of the point with component
  /// index f, cell cc (the cell above the face point along c) and d-velocity index v.
  void plusFlux(int d, std::size_t f, std::size_t cc, std::size_t v, double& convective, double& stress) const {
    const double* U = u_[c_].data().data();
    const double* E = eps_.data().data();
    const std::ptrdiff_t s = su_[d];
    double F;
    if (d == c_) {
      F = rho_ * E[cc] * 0.5 * (U[f] + U[f + s]);
      const double dP = (U[f + s] - U[f]) * invH_[c_];
      stress = E[cc] * (dP - 2.0 / 3.0 * div_.data()[cc]);
    } else {
      const std::size_t cm = cc - se_[c_];
      const double* V = V_[d];
      const std::size_t vm = v - vc_[d];
      const double vp = 0.5 * (V[v + vd_[d]] + V[vm + vd_[d]]);
      const double ep = 0.25 * (E[cc] + E[cm] + E[cc + se_[d]] + E[cm + se_[d]]);
      F = rho_ * ep * vp;
      stress = ep * ((V[v + vd_[d]] - V[vm + vd_[d]]) * invH_[c_]);
    }
    convective = F * faceValue<TVD>(F, U[f - s], U[f], U[f + s], U[f + 2 * s]);
  }

  const Field* u_;
  const Field& eps_;
  const std::vector<std::uint8_t>& mask_;
  Field& out_;
  int c_;
  double rho_, mu_;
  const Field& div_;
  std::ptrdiff_t su_[3], se_[3], vc_[3], vd_[3];
  double invH_[3];
  const double* V_[3];
  std::vector<Flux> yCarry_, zCarry_;
};

}  // namespace gf::fluid
