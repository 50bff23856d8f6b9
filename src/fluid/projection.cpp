// Incremental pressure-correction projection with the eps-weighted Poisson equation
//   div( eps a / (rho gamma0 eps/dt + K) grad phi ) = div(eps u*) + (eps - eps_old)/dt
//   u = u* - a / (rho gamma0 eps/dt + K) grad phi,   p += phi       (a = eps for model A, 1 for B)
// so that the corrected velocity satisfies the discrete continuity equation of seed 000 eq. 5.3.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/reduction.hpp"
#include "fluid/loops.hpp"
#include "fluid/solver.hpp"
#include "fluid/variable_density.hpp"
#include "parallel/reductions.hpp"

namespace gf::fluid {

namespace {
inline double avg(const double* a, std::size_t i, std::ptrdiff_t s) { return 0.5 * (a[i] + a[i - s]); }
}  // namespace

int Solver::teamSize() const {
  // Members own >= 1500 cells (fewer: a barrier costs more than the member's work).
  const std::int64_t cells = grid_.interiorCellCount();
  // (a decomposed grid: no plane teams; its ghost fills exchange with the neighbour ranks)
  if (twoD_ || cells >= kSerialCellsBelow || decomposition_->distributed()) return 1;
  return static_cast<int>(std::max<std::int64_t>(
      1, std::min<std::int64_t>({gf::threadCount(), grid_.cells[2], cells / 1500})));
}

double Solver::maxDivergence() const {
  const parallel::RankReductionScope ranks(*decomposition_);
  // Line by line; a maximum does not depend on the order.
  // The eps pair of the last step (epsStep_, epsOlder_): in a coupled run the coupler has
  // already replaced the coupling fields by those of the next step (eps^{n+2}, eps^{n+1}).
  const int nx = grid_.cells[0], ny = grid_.cells[1], nz = grid_.cells[2];
  const int dims = twoD_ ? 2 : 3;
  const double* E = (epsStepKept_ ? epsStep_ : coupling_.voidFraction).data().data();
  const double* Eo = (epsStepKept_ ? epsOlder_ : coupling_.voidFractionOld).data().data();
  const double dt = lastDt_;
  std::vector<double> lineMax(static_cast<std::size_t>(ny) * nz, 0.0);
  parallelFor(static_cast<std::int64_t>(ny) * nz, [&](std::int64_t line) {
    const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
    const std::size_t e0 = p_.index(0, j, k);
    const double* Ud[3];
    std::ptrdiff_t su[3], se[3];
    for (int a = 0; a < dims; ++a) {
      Ud[a] = u_[a].data().data() + u_[a].index(0, j, k);
      su[a] = u_[a].stride(a);
      se[a] = p_.stride(a);
    }
    const std::uint8_t* B = blocked_.data() + e0;
    double m = 0.0;
    for (int i = 0; i < nx; ++i) {
      if (B[i]) continue;
      const std::size_t cc = e0 + i;
      double div = 0.0;
      for (int a = 0; a < dims; ++a) {
        const double flux_hi = 0.5 * (E[cc] + E[cc + se[a]]) * Ud[a][i + su[a]];
        const double flux_lo = 0.5 * (E[cc] + E[cc - se[a]]) * Ud[a][i];
        div += (flux_hi - flux_lo) / grid_.spacing[a];
      }
      if (dt > 0.0) div += (E[cc] - Eo[cc]) / dt;
      m = std::max(m, std::abs(div));
    }
    lineMax[static_cast<std::size_t>(line)] = m;
  });
  return maxOfPartials(lineMax);
}

void Solver::balanceOutflow(double dt) {
  const double* E = coupling_.voidFraction.data().data();
  bool anyOutflow = false, anyPressure = false;
  // Outlet faces take the predicted velocity of their inner neighbour (zero gradient).
  for (int a = 0; a < (twoD_ ? 2 : 3); ++a)
    for (int s = 0; s < 2; ++s) {
      // (the domain's sides decide, the same on every rank; this rank's sides are set)
      const BoundaryType domainType = bc_.domainSide(a, s);
      anyOutflow = anyOutflow || domainType == BoundaryType::Outflow;
      anyPressure = anyPressure || domainType == BoundaryType::PressureOutlet;
      const BoundaryType t = bc_.at(a, s).type;
      if (!isOutlet(t)) continue;
      Field& u = u_[a];
      forEachBoundaryFace(a, s, [&](const int* face, const int* cell) {
        const std::size_t f = u.index(face[0], face[1], face[2]);
        const std::ptrdiff_t st = u.stride(a);
        u.data()[f] = blocked(cell[0], cell[1], cell[2]) ? 0.0 : u.data()[s == 0 ? f + st : f - st];
      });
    }
  if (!anyOutflow || anyPressure) return;
  // Zero-gradient outlets only: shift the outflow velocity so that mass is conserved globally
  // (the Poisson problem is then a compatible pure-Neumann problem).
  double net = 0.0, outflowArea = 0.0;
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i)
        net += grid_.cellVolume() *
               (coupling_.voidFraction(i, j, k) - coupling_.voidFractionOld(i, j, k)) / dt;
  for (int a = 0; a < (twoD_ ? 2 : 3); ++a) {
    if (bc_.periodic(a)) continue;
    const double area = grid_.cellVolume() / grid_.spacing[a];
    for (int s = 0; s < 2; ++s) {
      if (bc_.shared(a, s)) continue;
      const bool out = bc_.at(a, s).type == BoundaryType::Outflow;
      forEachBoundaryFace(a, s, [&](const int* face, const int* cell) {
        const double epsF = E[coupling_.voidFraction.index(cell[0], cell[1], cell[2])];
        const double outward = (s == 0 ? -1.0 : 1.0) * u_[a](face[0], face[1], face[2]);
        net += epsF * outward * area;
        if (out && !blocked(cell[0], cell[1], cell[2])) outflowArea += epsF * area;
      });
    }
  }
  std::tie(net, outflowArea) = sumAcrossRanks(std::pair<double, double>{net, outflowArea});
  if (outflowArea <= 0.0) return;
  const double shift = -net / outflowArea;  // added to the outward velocity
  for (int a = 0; a < (twoD_ ? 2 : 3); ++a)
    for (int s = 0; s < 2; ++s) {
      if (bc_.at(a, s).type != BoundaryType::Outflow) continue;
      forEachBoundaryFace(a, s, [&](const int* face, const int* cell) {
        if (!blocked(cell[0], cell[1], cell[2])) u_[a](face[0], face[1], face[2]) += (s == 0 ? -shift : shift);
      });
    }
}

void Solver::project(double dt, double g0) {
  const int nx = grid_.cells[0], ny = grid_.cells[1], nz = grid_.cells[2];
  const double* E = coupling_.voidFraction.data().data();
  const double* Eo = coupling_.voidFractionOld.data().data();
  const double* K = coupling_.dragCoefficient.data().data();
  const bool modelA = model_ == MomentumModel::A;
  const double timeCoeff = rho_ * g0 / dt;
  const int dims = twoD_ ? 2 : 3;
  // Does face (i,j,k) of component a take part in the pressure correction?
  auto coupled = [&](int a, int i, int j, int k) {
    const Field& u = u_[a];
    const int idx[3] = {i, j, k};
    const int n = grid_.cells[a];
    if (bc_.periodic(a) && idx[a] == n) return unknown_[a][u.index(i - (a == 0) * n, j - (a == 1) * n, k - (a == 2) * n)] != 0;
    if (bc_.shared(a, 1) && idx[a] == n) {
      // The upper rank's face 0 (a momentum unknown there unless a cell beside it is blocked).
      int below[3] = {i, j, k};
      below[a] = n - 1;
      return !blocked(below[0], below[1], below[2]) && !blocked(i, j, k);
    }
    if (unknown_[a][u.index(i, j, k)]) return true;
    if (idx[a] == 0 || idx[a] == n) {
      const int s = idx[a] == 0 ? 0 : 1;
      int cell[3] = {i, j, k};
      if (s == 1) cell[a] = n - 1;
      return bc_.at(a, s).type == BoundaryType::PressureOutlet && !blocked(cell[0], cell[1], cell[2]);
    }
    return false;
  };
  // Coefficient a / (rho gamma0 eps / dt + K) of the velocity correction at a face; with a VOF
  // mixture rho is the face density of the cells' mixture densities (fluid/variable_density.hpp).
  const double* RhoCell = vof_ ? rhoCell_.data().data() : nullptr;
  auto correctionCoeff = [&](int a, std::size_t cc) {
    const std::ptrdiff_t se = p_.stride(a);
    const double epsF = avg(E, cc, se);
    if (RhoCell)
      return projectionCoefficient(epsF, faceDensity(RhoCell[cc - se], RhoCell[cc]), g0 / dt, avg(K, cc, se), modelA);
    return (modelA ? epsF : 1.0) / (timeCoeff * epsF + avg(K, cc, se));
  };
  // Small grids: the coefficients and the right-hand side in one team region, the correction and
  // p += phi in another (threads split the z planes; the same values for any split).
  const int team = teamSize();
  auto inTeam = [&](TeamTuner& tuner, auto&& body) {
    if (team <= 1) return body(static_cast<const PlaneSlab*>(nullptr));
    runPlaneTeam(tuner, team, grid_.cells[2], [&](const PlaneSlab& slab) { body(&slab); });
  };
  auto range = [&](const PlaneSlab* slab, const std::array<int, 3>& points) {
    return slab ? std::pair<std::int64_t, std::int64_t>{slab->lineBegin(points), slab->lineEnd(points)}
                : std::pair<std::int64_t, std::int64_t>{0, -1};
  };
  const bool rebuild = !uniformCoupling_ || timeCoeff != poissonKey_ || vof_;
  // Faces of the pressure coefficients (bit 1) and of the velocity correction (bit 2), per
  // velocity point: fixed by the masks and boundary types, so evaluated once.
  if (pressureFaces_[0].size() != u_[0].data().size())
    for (int a = 0; a < 3; ++a) {
      const Field& u = u_[a];
      pressureFaces_[a].assign(u.data().size(), 0);
      correctionCoeff_[a].assign(u.data().size(), 0.0);
      if (a >= dims) continue;
      const auto& pts = u.points();
      const int n = grid_.cells[a];
      const bool periodic = bc_.periodic(a);
      for (int k = 0; k < pts[2]; ++k)
        for (int j = 0; j < pts[1]; ++j)
          for (int i = 0; i < pts[0]; ++i) {
            const std::size_t f = u.index(i, j, k);
            const int idx[3] = {i, j, k};
            const int along = idx[a];
            const bool boundary = along == 0 || along == n;
            // coupled(): a momentum unknown, or a boundary face (periodic duplicate, pressure outlet).
            const bool coefficient = unknown_[a][f] || (boundary && coupled(a, i, j, k));
            // Corrected: the last face of a periodic axis duplicates face 0.
            const bool corrected =
                unknown_[a][f] || (boundary && !(along == n && (periodic || bc_.shared(a, 1))) && coupled(a, i, j, k));
            pressureFaces_[a][f] = static_cast<std::uint8_t>((coefficient ? 1 : 0) | (corrected ? 2 : 0));
          }
    }
  std::array<std::vector<double>, 3>& T = poissonT_;
  std::array<bool, 6> dirichlet{};
  if (rebuild)
    for (int a = 0; a < 3; ++a) {
      std::array<int, 3> fn = grid_.cells;
      fn[a] += 1;
      // Faces of the dimensions: every one written below (0 off the coefficient faces).
      if (a < dims) T[a].resize(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2]);
      else T[a].assign(static_cast<std::size_t>(fn[0]) * fn[1] * fn[2], 0.0);
      if (a < dims)
        for (int s = 0; s < 2; ++s) dirichlet[2 * a + s] = bc_.domainSide(a, s) == BoundaryType::PressureOutlet;
    }
  const double V = grid_.cellVolume();
  inTeam(projectTeam_[0], [&](const PlaneSlab* slab) {
    if (rebuild)
      for (int a = 0; a < dims; ++a) {
        std::array<int, 3> fn = grid_.cells;
        fn[a] += 1;
        const double areaOverH = grid_.cellVolume() / (grid_.spacing[a] * grid_.spacing[a]);
        const Field& u = u_[a];
        const std::ptrdiff_t se = p_.stride(a);
        const auto [lb, le] = range(slab, fn);
        forLines(static_cast<std::int64_t>(fn[1]) * fn[2], lb, le, [&](std::int64_t line) {
          const int j = static_cast<int>(line % fn[1]), k = static_cast<int>(line / fn[1]);
          const std::size_t f0 = u.index(0, j, k), e0 = p_.index(0, j, k);
          const std::uint8_t* PF = pressureFaces_[a].data() + f0;
          double* C = correctionCoeff_[a].data() + f0;
          double* Tl = T[a].data() + fn[0] * static_cast<std::size_t>(line);
          for (int i = 0; i < fn[0]; ++i) {
            if (!(PF[i] & 1)) {
              Tl[i] = 0.0;
              continue;
            }
            const std::size_t cc = e0 + i;
            const double epsF = avg(E, cc, se);
            // correctionCoeff(a, cc), kept for the velocity correction below.
            C[i] = correctionCoeff(a, cc);
            Tl[i] = epsF * C[i] * areaOverH;
          }
        });
      }
    // Right-hand side: -(net eps u* outflow + V d eps/dt) per cell.
    const auto [lb, le] = range(slab, grid_.cells);
    forLines(static_cast<std::int64_t>(ny) * nz, lb, le, [&](std::int64_t line) {
      const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
      const std::size_t e0 = p_.index(0, j, k);
      const double* Ud[3];
      std::ptrdiff_t su[3], se[3];
      double area[3];
      for (int a = 0; a < dims; ++a) {
        Ud[a] = u_[a].data().data() + u_[a].index(0, j, k);
        su[a] = u_[a].stride(a);
        se[a] = p_.stride(a);
        area[a] = V / grid_.spacing[a];
      }
      double* rhs = poissonRhs_.data() + static_cast<std::size_t>(nx) * line;
      double* guess = poissonX_.data() + static_cast<std::size_t>(nx) * line;
      const std::uint8_t* B = blocked_.data() + e0;
      if (uniformCoupling_) {
        // eps = eps_old = 1 (ghosts included): the expression below without reading them (the
        // same bits: V (1 - 1) / dt = +0, the face eps 0.5 (1 + 1) = 1 and 1 u = u exactly).
        for (int i = 0; i < nx; ++i) {
          if (B[i]) {
            guess[i] = 0.0;
            rhs[i] = 0.0;
            continue;
          }
          double net = 0.0;
          for (int a = 0; a < dims; ++a) net += area[a] * (Ud[a][i + su[a]] - Ud[a][i]);
          rhs[i] = -net;
        }
        return;
      }
      for (int i = 0; i < nx; ++i) {
        if (B[i]) {
          guess[i] = 0.0;  // otherwise: previous increment as initial guess
          rhs[i] = 0.0;
          continue;
        }
        const std::size_t cc = e0 + i;
        double net = V * (E[cc] - Eo[cc]) / dt;
        for (int a = 0; a < dims; ++a)
          net += area[a] * (avg(E, cc + se[a], se[a]) * Ud[a][i + su[a]] - avg(E, cc, se[a]) * Ud[a][i]);
        rhs[i] = -net;
      }
    });
  });
  if (rebuild) {
    std::array<bool, 3> periodic{bc_.domainPeriodic(0), bc_.domainPeriodic(1), bc_.domainPeriodic(2) && !twoD_};
    // (a solver that owns its whole grid keeps hypre to its own process)
    if (hyprePressure_ && !hypre_) hypre_ = std::make_shared<HyprePressure>(!decomposition_->distributed());
    if (gatheredPressure_ && !gathered_) gathered_ = std::make_shared<GatheredPressure>();
    const PressureBox box = decomposition_->distributed()
                                ? PressureBox{bc_.domainCells, decomposition_->cellOffset(), grid_.cells}
                                : PressureBox::whole(grid_.cells);
    if (hypre_) hypre_->setup(box, periodic, T, dirichlet);
    else if (gathered_) gathered_->setup(box, periodic, T, dirichlet);
    else poisson_.setup(grid_.cells, periodic, T, dirichlet);
    poissonKey_ = uniformCoupling_ && !vof_ ? timeCoeff : -1.0;
  }
  // g.x at the centre of the boundary face of `cell` on side s of axis a.
  auto outletGravityPotential = [&](int a, int s, const int* cell) {
    Vec3 x = grid_.cellCentre(cell[0], cell[1], cell[2]);
    x[a] += (s == 0 ? -0.5 : 0.5) * grid_.spacing[a];
    return dot(gravity_, x);
  };
  // Pressure outlets: phi_b = p_out - p^n_b with p^n_b the interior pressure extrapolated
  // linearly to the boundary, so that at convergence the pressure meets p_out there. Cells of the
  // z planes [kBegin, kEnd) only.
  auto forOutletCells = [&](int kBegin, int kEnd, auto&& body) {
    for (int a = 0; a < dims; ++a)
      for (int s = 0; s < 2; ++s) {
        if (bc_.at(a, s).type != BoundaryType::PressureOutlet) continue;
        const int n = grid_.cells[a], b1 = (a + 1) % 3, b2 = (a + 2) % 3;
        for (int q = 0; q < grid_.cells[b2]; ++q)
          for (int p = 0; p < grid_.cells[b1]; ++p) {
            int cell[3];
            cell[a] = s == 0 ? 0 : n - 1;
            cell[b1] = p;
            cell[b2] = q;
            if (cell[2] < kBegin || cell[2] >= kEnd || blocked(cell[0], cell[1], cell[2])) continue;
            const std::size_t cc = p_.index(cell[0], cell[1], cell[2]);
            const std::ptrdiff_t inward = (s == 0 ? 1 : -1) * p_.stride(a);
            const double pb = n >= 2 ? 1.5 * p_.data()[cc] - 0.5 * p_.data()[cc + inward] : p_.data()[cc];
            const std::size_t face = s == 0 ? cc : cc + p_.stride(a);  // cell index of the face's + side
            // (VOF: p_ holds p* = p - rho g.x; the outlet's p* with the boundary cell's rho)
            const double target = RhoCell ? bc_.at(a, s).pressure - RhoCell[cc] * outletGravityPotential(a, s, cell)
                                          : bc_.at(a, s).pressure;
            body(cell, cc, face, inward, target - pb, a);
          }
      }
  };
  forOutletCells(0, nz, [&](const int* cell, std::size_t, std::size_t face, std::ptrdiff_t, double phiB, int a) {
    const double areaOverH = grid_.cellVolume() / (grid_.spacing[a] * grid_.spacing[a]);
    const double epsF = avg(E, face, p_.stride(a));
    const double T = epsF * correctionCoeff(a, face) * areaOverH;
    poissonRhs_[static_cast<std::size_t>(cell[0]) + static_cast<std::size_t>(nx) * (cell[1] + static_cast<std::size_t>(ny) * cell[2])] +=
        2.0 * T * phiB;
  });
  const PoissonResult res =
      hypre_      ? hypre_->solve(poissonX_, poissonRhs_, pressureTolerance_, pressureMaxIterations_)
      : gathered_ ? gathered_->solve(poissonX_, poissonRhs_, pressureTolerance_, pressureMaxIterations_)
                  : poisson_.solve(poissonX_, poissonRhs_, pressureTolerance_, pressureMaxIterations_);
  stats_.pressureIterations = res.iterations;
  stats_.pressureResidual = res.relativeResidual;
  const double* Phi = phi_.data().data();
  // eps = 1, K = 0: the same coefficient everywhere (no division per face); not with a mixture.
  const double uniformCoeff = 1.0 / timeCoeff;
  const bool uniformCorrection = uniformCoupling_ && !vof_;
  // A team fills the ghosts of phi, u and p in its region, each member those of its planes (the
  // z sides from the first and last two planes: members own >= 2 planes, z not periodic).
  const bool fillInTeam = team > 1 && !bc_.periodic(2) && nz >= 2 * team;
  inTeam(projectTeam_[1], [&](const PlaneSlab* slab) {
    // phi = the increment, with its ghosts.
    // (members' own planes, or all on one member)
    const bool own = slab && fillInTeam;
    if (own || !slab || slab->first) {
      const auto [lb, le] = own ? range(slab, grid_.cells) : std::pair<std::int64_t, std::int64_t>{0, -1};
      forLines(static_cast<std::int64_t>(ny) * nz, lb, le, [&](std::int64_t line) {
        const int j = static_cast<int>(line % ny), k = static_cast<int>(line / ny);
        double* phiLine = phi_.data().data() + phi_.index(0, j, k);
        const double* x = poissonX_.data() + static_cast<std::size_t>(nx) * line;
        for (int i = 0; i < nx; ++i) phiLine[i] = x[i];
      });
      const GhostPlanes planes = own ? slab->ghostPlanes(grid_.cells) : GhostPlanes{};
      fillCellGhostsPlanes(phi_, bc_, CellGhostKind::PressureIncrement, planes);
      forOutletCells(planes.kBegin, planes.kEnd < 0 ? nz : planes.kEnd,
                     [&](const int*, std::size_t cc, std::size_t, std::ptrdiff_t inward, double phiB, int) {
                       phi_.data()[cc - inward] = 2.0 * phiB - phi_.data()[cc];
                     });
    }
#pragma omp barrier
    for (int a = 0; a < dims; ++a) {
      Field& u = u_[a];
      const auto& pts = u.points();
      const std::ptrdiff_t se = p_.stride(a);
      const double invH = 1.0 / grid_.spacing[a];
      const auto [lb, le] = range(slab, pts);
      forLines(static_cast<std::int64_t>(pts[1]) * pts[2], lb, le, [&](std::int64_t line) {
        const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
        const std::size_t f0 = u.index(0, j, k), e0 = p_.index(0, j, k);
        double* U = u.data().data() + f0;
        // Faces off the momentum unknowns take part only on a boundary (pressure outlets).
        const std::uint8_t* PF = pressureFaces_[a].data() + f0;
        // Non-uniform coupling: the coefficients were rebuilt above for this step (the same
        // correctionCoeff(a, cc) values).
        const double* C = correctionCoeff_[a].data() + f0;
        for (int i = 0; i < pts[0]; ++i) {
          if (!(PF[i] & 2)) continue;
          const std::size_t cc = e0 + i;
          const double coeff = uniformCorrection ? uniformCoeff : C[i];
          U[i] -= coeff * (Phi[cc] - Phi[cc - se]) * invH;
        }
      });
      if (own) fillVelocityGhostsPlanes(u, a, bc_, GhostMode::Full, slab->ghostPlanes(pts));
    }
    // p += phi over the whole array (ghosts included): the member's planes (the first and last
    // members also the ghost planes).
    double* P = p_.data().data();
    const int g = grid_.ghosts;
    const std::size_t b = !slab || slab->first ? 0 : p_.index(-g, -g, slab->k0);
    const std::size_t e = !slab || slab->last ? p_.data().size() : p_.index(-g, -g, slab->k1);
    if (!slab) {
      parallelForElements(static_cast<std::int64_t>(p_.data().size()), [&](std::int64_t q) { P[q] += Phi[q]; });
    } else {
      for (std::size_t q = b; q < e; ++q) P[q] += Phi[q];
    }
    if (own) fillCellGhostsPlanes(p_, bc_, CellGhostKind::Pressure, slab->ghostPlanes(grid_.cells));
  });
  if (!fillInTeam) {
    for (int a = 0; a < dims; ++a) fillVelocityGhosts(u_[a], a, bc_, GhostMode::Full);
    fillCellGhosts(p_, bc_, CellGhostKind::Pressure);
  }
  ghostsFresh_ = dims == 3;  // (2D: w is not refilled here)
}

void Solver::controlFlowRate(double dt, double g0) {
  // Uniform correction of the driving-axis velocity so the mean superficial velocity equals
  // bulk_velocity; the pressure gradient that produces it is accumulated in drive_.
  const int a = driveAxis_;
  Field& u = u_[a];
  const double* E = coupling_.voidFraction.data().data();
  const std::ptrdiff_t se = p_.stride(a);
  const auto& list = unknownList_[a];
  double flux = 0.0, epsSum = 0.0;
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i) {
        const std::size_t cc = p_.index(i, j, k);
        const double epsF = 0.5 * (E[cc] + E[cc - se]);
        flux += epsF * u(i, j, k);
        if (unknown_[a][u.index(i, j, k)]) epsSum += epsF;
      }
  std::tie(flux, epsSum) = sumAcrossRanks(std::pair<double, double>{flux, epsSum});
  double count = static_cast<double>(grid_.interiorCellCount());
  if (decomposition_->distributed())
    count = static_cast<double>(bc_.domainCells[0]) * bc_.domainCells[1] * bc_.domainCells[2];
  // (no unknowns: epsSum = 0)
  if (epsSum <= 0.0) return;
  const double delta = (bulkVelocity_ - flux / count) * count / epsSum;
  for (auto f : list) u.data()[f] += delta;
  fillVelocityGhosts(u, a, bc_, GhostMode::Full);
  drive_ += rho_ * g0 * delta / dt;
}

}  // namespace gf::fluid
