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

  /// No work after a point's convection.
  struct NoEpilogue {
    void point(std::size_t, std::size_t, double) {}
    void line(std::int64_t) {}
  };

  /// Grid lines [lb, le) of the component (line = j + points[1] k), in order, on this thread.
  /// after.point(f, cc, N_f) runs right after the convection N_f of each unknown point f (cell
  /// cc above it along c), after.line(line) at the end of each line.
  template <class After = NoEpilogue>
  void run(std::int64_t lb, std::int64_t le, After&& after = After{}) {
    // The component as a template argument: the along / across branches of the face fluxes and
    // the stride choices are resolved at compile time (same arithmetic).
    if (c_ == 0) runComponent<0>(lb, le, after);
    else if (c_ == 1) runComponent<1>(lb, le, after);
    else runComponent<2>(lb, le, after);
  }

 private:
  template <int C, class After>
  void runComponent(std::int64_t lb, std::int64_t le, After& after) {
    const Field& uc = u_[C];
    const auto& pts = uc.points();
    const int nx = pts[0], ny = pts[1];
    yCarry_.assign(static_cast<std::size_t>(nx), Flux{});
    zCarry_.assign(static_cast<std::size_t>(nx) * ny, Flux{});
    double* O = out_.data().data();
    const std::uint8_t* M = mask_.data();
    for (std::int64_t line = lb; line < le; ++line) {
      const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
      const bool yRun = j > 0 && line - 1 >= lb;    // line (j - 1, k) was just done
      const bool zRun = line - ny >= lb;            // line (j, k - 1) was done in this run
      const std::size_t f0 = uc.index(0, j, k), e0 = eps_.index(0, j, k);
      std::size_t v0[3];
      for (int d = 0; d < 3; ++d) v0[d] = u_[d].index(0, j, k);
      Flux xCarry;
      Flux* yLine = yCarry_.data();
      Flux* zLine = zCarry_.data() + static_cast<std::size_t>(nx) * j;
      for (int i = 0; i < nx; ++i) {
        Flux& yc = yLine[i];
        Flux& zc = zLine[i];
        if (!yRun) yc.valid = false;
        if (!zRun) zc.valid = false;
        const std::size_t f = f0 + i;
        if (!M[f]) {
          O[f] = 0.0;
          xCarry.valid = yc.valid = zc.valid = false;
          continue;
        }
        const std::size_t cc = e0 + i;
        Flux* carry[3] = {&xCarry, &yc, &zc};
        double N = 0.0, stress[3] = {0.0, 0.0, 0.0};
        auto direction = [&]<int D>() {
          // Scalars, not Flux copies: a 16-byte copy of two separately stored doubles stalls on
          // store forwarding (40 % of this loop in perf).
          const std::size_t vi = v0[D] + i;
          double minusConv, minusStress, plusConv, plusStress;
          if (carry[D]->valid) {
            minusConv = carry[D]->convective;
            minusStress = carry[D]->stress;
          } else {
            plusFlux<C, D>(f - su_[D], cc - se_[D], vi - vd_[D], minusConv, minusStress);
          }
          plusFlux<C, D>(f, cc, vi, plusConv, plusStress);
          N += (plusConv - minusConv) * invH_[D];
          stress[D] = (plusStress - minusStress) * invH_[D];
          carry[D]->convective = plusConv;
          carry[D]->stress = plusStress;
          carry[D]->valid = true;
        };
        direction.template operator()<0>();
        direction.template operator()<1>();
        if constexpr (DIMS == 3) direction.template operator()<2>();
        // div(eps mu [(grad u)^T - 2/3 (div u) I]) for component c: the c term, then the others.
        double T = stress[C];
        for (int d = 0; d < DIMS; ++d)
          if (d != C) T += stress[d];
        const double result = N - mu_ * T;
        O[f] = result;
        after.point(f, cc, result);
      }
      after.line(line);
    }
  }

  struct Flux {
    double convective = 0.0, stress = 0.0;
    bool valid = false;
  };

  /// Fluxes through the plus face along D of the control volume of the point with component
  /// index f, cell cc (the cell above the face point along C) and D-velocity index v.
  template <int C, int D>
  void plusFlux(std::size_t f, std::size_t cc, std::size_t v, double& convective, double& stress) const {
    const double* U = u_[C].data().data();
    const double* E = eps_.data().data();
    const std::ptrdiff_t s = su_[D];
    double F;
    if constexpr (D == C) {
      F = rho_ * E[cc] * 0.5 * (U[f] + U[f + s]);
      const double dP = (U[f + s] - U[f]) * invH_[C];
      stress = E[cc] * (dP - 2.0 / 3.0 * div_.data()[cc]);
    } else {
      const std::size_t cm = cc - se_[C];
      const double* V = V_[D];
      const std::size_t vm = v - vc_[D];
      const double vp = 0.5 * (V[v + vd_[D]] + V[vm + vd_[D]]);
      const double ep = 0.25 * (E[cc] + E[cm] + E[cc + se_[D]] + E[cm + se_[D]]);
      F = rho_ * ep * vp;
      stress = ep * ((V[v + vd_[D]] - V[vm + vd_[D]]) * invH_[C]);
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
