// Passive scalar: eps dT/dt + eps u . grad T = div(eps D grad T) + eps S, finite volume on cell
// centres, convective fluxes with the momentum scheme (central or van Leer) written in the
// advective form sum Q_f (T_f - T_c) (bounded for a TVD face value), explicit SSP-RK2 (Heun;
// Shu & Osher 1988) with substeps so that the summed outflow Courant and diffusion numbers stay
// <= 0.4.
#include <cmath>

#include "fluid/loops.hpp"
#include "fluid/schemes.hpp"
#include "fluid/solver.hpp"

namespace gf::fluid {

namespace {

template <bool TVD>
void scalarRate(const Field& T, const Field u[3], const Field& eps, const std::vector<std::uint8_t>& blocked,
                double D, double S, int dims, std::vector<double>& out) {
  const CartesianGrid& g = T.grid();
  const int nx = g.cells[0], ny = g.cells[1], nz = g.cells[2];
  const double* Q = T.data().data();
  const double* E = eps.data().data();
  parallelFor(static_cast<std::int64_t>(ny) * nz, [&](std::int64_t line) {
    const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = T.index(i, j, k);
      if (blocked[c]) {
        out[c] = 0.0;
        continue;
      }
      double rate = 0.0;
      for (int a = 0; a < dims; ++a) {
        const std::ptrdiff_t s = T.stride(a);
        const std::size_t f = u[a].index(i, j, k);
        const double uLo = u[a].data()[f], uHi = u[a].data()[f + u[a].stride(a)];
        const double eLo = 0.5 * (E[c] + E[c - s]), eHi = 0.5 * (E[c] + E[c + s]);
        const double qHi = eHi * uHi, qLo = eLo * uLo;  // volumetric flux per area, along +a
        const double tHi = faceValue<TVD>(qHi, Q[c - s], Q[c], Q[c + s], Q[c + 2 * s]);
        const double tLo = faceValue<TVD>(qLo, Q[c - 2 * s], Q[c - s], Q[c], Q[c + s]);
        const double h = g.spacing[a];
        rate -= (qHi * (tHi - Q[c]) - qLo * (tLo - Q[c])) / h;
        const double dHi = blocked[c + s] ? 0.0 : eHi * (Q[c + s] - Q[c]);
        const double dLo = blocked[c - s] ? 0.0 : eLo * (Q[c] - Q[c - s]);
        rate += D * (dHi - dLo) / (h * h);
      }
      out[c] = rate / E[c] + S;
    }
  });
}

}  // namespace

void Solver::advanceScalar(double dt) {
  const int dims = twoD_ ? 2 : 3;
  // Substeps from the summed outflow Courant number and the explicit diffusion limit.
  double cflRate = 0.0;
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i) {
        double r = 0.0;
        for (int a = 0; a < dims; ++a) {
          int hi[3] = {i, j, k};
          hi[a] += 1;
          r += std::max(std::abs(u_[a](i, j, k)), std::abs(u_[a](hi[0], hi[1], hi[2]))) / grid_.spacing[a];
        }
        cflRate = std::max(cflRate, r);
      }
  double diffRate = 0.0;
  for (int a = 0; a < dims; ++a) diffRate += 2.0 * scalarDiffusivity_ / (grid_.spacing[a] * grid_.spacing[a]);
  const double rate = std::max(cflRate, diffRate);
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt * rate / 0.4)));
  const double h = dt / substeps;
  std::vector<double> k1(scalar_.data().size(), 0.0), k2(scalar_.data().size(), 0.0);
  Field stage = scalar_;
  const bool tvd = scheme_ == ConvectionScheme::VanLeer;
  auto evaluate = [&](const Field& T, std::vector<double>& out) {
    if (tvd) scalarRate<true>(T, u_, coupling_.voidFraction, blocked_, scalarDiffusivity_, scalarSource_, dims, out);
    else scalarRate<false>(T, u_, coupling_.voidFraction, blocked_, scalarDiffusivity_, scalarSource_, dims, out);
  };
  const auto n = static_cast<std::int64_t>(scalar_.data().size());
  for (int s = 0; s < substeps; ++s) {
    fillCellGhosts(scalar_, bc_, CellGhostKind::Scalar);
    evaluate(scalar_, k1);
    parallelForElements(n, [&](std::int64_t q) { stage.data()[q] = scalar_.data()[q] + h * k1[q]; });
    fillCellGhosts(stage, bc_, CellGhostKind::Scalar);
    evaluate(stage, k2);
    parallelForElements(n, [&](std::int64_t q) {
      scalar_.data()[q] = 0.5 * scalar_.data()[q] + 0.5 * (stage.data()[q] + h * k2[q]);
    });
  }
  fillCellGhosts(scalar_, bc_, CellGhostKind::Scalar);
}

}  // namespace gf::fluid
