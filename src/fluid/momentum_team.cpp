// Momentum predictor of a coupled (eps-varying) step in one parallel region: convection, the
// right-hand sides and the Jacobi sweeps of all three velocity components, the threads splitting
// the z planes (the long axis of a pseudo-2D bed: a 2 x 30 x 90 grid has 2-point x lines, too
// short to split). A thread team per loop cost more than the loop on such grids (5400 cells, a
// few microseconds per loop); here a step has 4 + (sweeps) barriers. Every value is computed
// with the arithmetic of the loop-by-loop path (computeConvection, assembleMomentum,
// solveHelmholtz's Jacobi branch): the same velocity for any thread count. Norms are summed per
// grid line in line order (deterministic; they only decide when to stop).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <omp.h>

#include "core/reduction.hpp"
#include "fluid/loops.hpp"
#include "fluid/solver.hpp"
#include "fluid/staggered_eps.hpp"
#include "parallel/halo.hpp"

namespace gf::fluid {

namespace {

// Team members own at least this many cells (fewer: the sweeps are shorter than a barrier).
constexpr std::int64_t kTeamCellsPerThread = 1500;

/// Exact Jacobi diagonal terms of the no-slip closure: solveHelmholtz adds 2 w_d eps_f to the
/// rows next to walls and inlets of each tangential direction d.
struct ClosureRows {
  bool lo[3] = {false, false, false}, hi[3] = {false, false, false};
  int n[3] = {1, 1, 1};
};

/// Jacobi rows (diagonal, inverse closed diagonal, control-volume face eps) of the unknowns on
/// lines [lb, le) of component c, for the operator (rho gamma0 eps_f/dt + K_f) x - div(mu eps grad x)
/// in the arithmetic of helmholtzKernel<false, 3> and solveHelmholtz's inverse diagonal. They
/// depend only on eps and K: computed once per step, not in each of the sweeps.
template <class Row>
void buildJacobiRows(const Field& x, Row* rows, const std::int64_t* list, const std::int64_t* lineStart,
                     const Field& eps, const Field& K, int c, double mu, double timeCoeff, const ClosureRows& closure,
                     std::int64_t lb, std::int64_t le) {
  const CartesianGrid& g = x.grid();
  const auto& pts = x.points();
  const double* E = eps.data().data();
  const double* Kd = K.data().data();
  std::ptrdiff_t se[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    se[d] = eps.stride(d);
    w[d] = mu / (g.spacing[d] * g.spacing[d]);
  }
  for (std::int64_t line = lb; line < le; ++line) {
    const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
    const auto f0 = static_cast<std::int64_t>(x.index(0, j, k));
    const std::size_t e0 = eps.index(0, j, k);
    for (std::int64_t q = lineStart[line]; q < lineStart[line + 1]; ++q) {
      const int i = static_cast<int>(list[q] - f0);
      Row& row = rows[q];
      const std::size_t cc = e0 + i, cm = cc - se[c];
      double diag = timeCoeff * 0.5 * (E[cc] + E[cm]) + 0.5 * (Kd[cc] + Kd[cm]);
      for (int d = 0; d < 3; ++d) {
        const auto [ep, em] = controlVolumeFaceEps(E, cc, cm, se[d], d == c);
        row.ep[d] = ep;
        row.em[d] = em;
        diag += w[d] * (ep + em);
      }
      double D = diag;
      const int idx[3] = {i, j, k};
      for (int d = 0; d < 3; ++d) {
        if (d == c) continue;
        const double epsF = 0.5 * (E[cc] + E[cm]);
        if (closure.lo[d] && idx[d] == 0) D += 2.0 * w[d] * epsF;
        if (closure.hi[d] && idx[d] == closure.n[d] - 1) D += 2.0 * w[d] * epsF;
      }
      row.diag = diag;
      row.invD = 1.0 / D;
    }
  }
}

/// One Jacobi sweep y = x + D^-1 (b - A x) at the unknowns of lines [lb, le) of component c
/// (rows from buildJacobiRows; y equals x at the other points of the lines: copied once per step).
/// partial[line] = |b - A x|^2 of the line.
template <class Row>
void jacobiSweepRows(const Field& x, Field& y, const double* B, const Row* rows, const std::int64_t* list,
                     const std::int64_t* lineStart, double mu, std::int64_t lb, std::int64_t le, double* partial) {
  const CartesianGrid& g = x.grid();
  const double* X = x.data().data();
  double* Y = y.data().data();
  std::ptrdiff_t sx[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    sx[d] = x.stride(d);
    w[d] = mu / (g.spacing[d] * g.spacing[d]);
  }
  for (std::int64_t line = lb; line < le; ++line) {
    double acc = 0.0;
    for (std::int64_t q = lineStart[line]; q < lineStart[line + 1]; ++q) {
      const auto f = static_cast<std::size_t>(list[q]);
      const Row& row = rows[q];
      double off = 0.0;
      for (int d = 0; d < 3; ++d) off += w[d] * (row.ep[d] * X[f + sx[d]] + row.em[d] * X[f - sx[d]]);
      const double r = B[f] - (row.diag * X[f] - off);
      Y[f] = X[f] + r * row.invD;
      acc += r * r;
    }
    partial[line] = acc;
  }
}

}  // namespace

bool Solver::predictMomentumTeam(double dt, double g0, double g1, double g2, double e1, double e2) {
  if (uniformCoupling_ || twoD_ || bc_.periodic(2) || grid_.cells[2] < 2) return false;
  // A decomposed grid: a team of one per rank (its MPI calls on the calling thread), the three
  // components' ghosts exchanged with the neighbour ranks in one message per sweep, and the sums and
  // the eps range combined across the ranks (every rank takes the same decisions).
  const bool distributed = decomposition_->distributed();
  double offRatio = 0.0;
  for (int d = 0; d < 3; ++d) offRatio += 2.0 * mu_ / (grid_.spacing[d] * grid_.spacing[d]);
  offRatio /= rho_ * g0 / dt + offRatio;
  if (!(offRatio < 0.6)) return false;  // BiCGStab (solveHelmholtz)
  const int nz = grid_.cells[2];
  // Team size: every member owns >= 2 planes (the z ghosts are filled from the two end planes)
  // and kTeamCellsPerThread cells.
  const std::int64_t cells = grid_.interiorCellCount();
  int team = std::min<std::int64_t>({gf::threadCount(), nz / 2, std::max<std::int64_t>(1, cells / kTeamCellsPerThread)});
  team = distributed ? 1 : momentumTeam_.pick(std::max(team, 1));
  const double started = TeamTuner::now();
  if (cellDivergence_.data().size() != p_.data().size()) cellDivergence_ = Field(grid_);
  for (int c = 0; c < 3; ++c) {
    const auto& pts = u_[c].points();
    const auto lines = static_cast<std::size_t>(pts[1]) * pts[2];
    for (auto& v : teamPartial_[c]) v.resize(lines);  // every line written before it is summed
    jacobiRows_[c].resize(unknownList_[c].size());
  }
  ClosureRows closure;
  for (int d = 0; d < 3; ++d) {
    closure.n[d] = grid_.cells[d];
    for (int side = 0; side < 2; ++side) {
      const BoundaryType type = bc_.at(d, side).type;
      (side == 0 ? closure.lo : closure.hi)[d] = type == BoundaryType::Wall || type == BoundaryType::Inlet;
    }
  }
  const double timeCoeff = rho_ * g0 / dt;
  // Jacobi residual contraction bound: r_{s+1} = (I - A D^-1) r_s, whose entries are the
  // off-diagonal couplings and the diagonal terms D lacks or adds (slip and wall closures), each
  // at most (4/3) w_max eps_max, at most 10 of them (in w_max eps_max units) per row and per
  // column, over D >= rho gamma0 eps_min / dt; ||M||_2 <= sqrt(||M||_1 ||M||_inf). A sweep whose
  // residual r_s satisfies 2 bound r_s <= tol has produced an iterate with ||r_{s+1}|| <= tol / 2:
  // it is accepted without the sweep that would only confirm it (the same iterate as before).
  // min and max of eps over the member's planes (exact whatever the order or split: four
  // independent lanes, which vectorise; std::minmax_element is one serial chain, 2 % of a bed
  // fluid step), combined after a barrier into the contraction bound by every member.
  double wMax = 0.0;
  for (int d = 0; d < 3; ++d) wMax = std::max(wMax, mu_ / (grid_.spacing[d] * grid_.spacing[d]));
  auto epsRange = [&](std::size_t begin, std::size_t end, double& lo, double& hi) {
    const double* e = coupling_.voidFraction.data().data();
    double lo4[4], hi4[4];
    for (int q = 0; q < 4; ++q) lo4[q] = hi4[q] = e[begin];
    std::size_t q = begin;
    for (; q + 4 <= end; q += 4)
      for (int l = 0; l < 4; ++l) {
        lo4[l] = std::min(lo4[l], e[q + l]);
        hi4[l] = std::max(hi4[l], e[q + l]);
      }
    for (; q < end; ++q) {
      lo4[0] = std::min(lo4[0], e[q]);
      hi4[0] = std::max(hi4[0], e[q]);
    }
    lo = std::min(std::min(lo4[0], lo4[1]), std::min(lo4[2], lo4[3]));
    hi = std::max(std::max(hi4[0], hi4[1]), std::max(hi4[2], hi4[3]));
  };
  std::vector<double>& memberRange = epsMemberRange_;  // lo, hi per member
  memberRange.assign(2 * static_cast<std::size_t>(std::max(team, 1)), 0.0);
  constexpr int kMaxSweeps = 40;  // as solveHelmholtz's Jacobi branch; BiCGStab takes over after
  int iterations[3] = {0, 0, 0};
  bool converged[3] = {true, true, true};
  bool inY[3] = {false, false, false};  // the result lies in precY_[c]
  const int g = grid_.ghosts;
  gf::TeamBarrier barrier(team);  // (one per Jacobi sweep: a spin barrier, core/parallel.hpp)
  auto member = [&]() {
    const PlaneSlab slab = PlaneSlab::ofCallingMember(nz, team);
    // Flat range [begin, end) of this member's planes of a field (ghost rows included; the first
    // and last members also take the ghost planes): element-wise work on whole arrays.
    auto flatRange = [&](const Field& f) {
      const std::size_t b = slab.first ? 0 : f.index(-g, -g, slab.k0);
      const std::size_t e = slab.last ? f.data().size() : f.index(-g, -g, slab.k1);
      return std::pair<std::size_t, std::size_t>{b, e};
    };
    computeCellDivergence(&slab);
    {
      const auto [b, e] = flatRange(coupling_.voidFraction);
      const int t = team > 1 ? omp_get_thread_num() : 0;
      epsRange(b, e, memberRange[2 * t], memberRange[2 * t + 1]);
    }
    barrier.wait();
    // Convection and right-hand sides in one pass; ||b||^2 per line into teamPartial_[c][0].
    double* const bPartial[3] = {teamPartial_[0][0].data(), teamPartial_[1][0].data(), teamPartial_[2][0].data()};
    convectAndAssemble(slab, dt, g1, g2, e1, e2, bPartial);
    for (int c = 0; c < 3; ++c) {
      const auto& pts = u_[c].points();
      if (!unknownList_[c].empty())
        buildJacobiRows(u_[c], jacobiRows_[c].data(), unknownList_[c].data(), unknownLineStart_[c].data(),
                        coupling_.voidFraction, coupling_.dragCoefficient, c, mu_, timeCoeff, closure,
                        slab.lineBegin(pts), slab.lineEnd(pts));
    }
    barrier.wait();  // convection read u^n of the neighbouring planes
    for (int c = 0; c < 3; ++c) {
      // Initial guess (solveHelmholtz): 2 u^n - u^{n-1} + last step's extrapolation error;
      // u^{n-1} <- u^n everywhere (ghosts included).
      Field& x = u_[c];
      double* X = x.data().data();
      double* Uo = uOld_[c].data().data();
      double* G = guessError_[c].data().data();
      double* Y = precY_[c].data().data();
      const std::uint8_t* M = unknown_[c].data();
      const auto [b, e] = flatRange(x);
      // Selections, not branches (the same values; vectorisable): the sweeps write y at the
      // unknowns only, so its other points take u^n here.
      for (std::size_t q = b; q < e; ++q) {
        const double un = X[q];
        const bool unknown = M[q] != 0;
        const double extrapolated = 2.0 * un - Uo[q];
        const double g = G[q];
        X[q] = unknown ? extrapolated + g : un;
        G[q] = unknown ? extrapolated : g;
        Y[q] = unknown ? Y[q] : un;
        Uo[q] = un;
      }
    }
    if (distributed) parallel::fillGhosts(std::vector<Field*>{&u_[0], &u_[1], &u_[2]}, *decomposition_);
    for (int c = 0; c < 3; ++c) {
      const auto& pts = u_[c].points();
      fillVelocityStencilGhostsSlab(u_[c], c, bc_, slab.k0, slab.planeEnd(pts), slab.first, slab.last);
    }
    barrier.wait();
    // Every member takes the same decisions from the same line sums (no further communication).
    double contraction = std::numeric_limits<double>::infinity();
    {
      const int members = team > 1 ? omp_get_num_threads() : 1;
      double lo = memberRange[0], hi = memberRange[1];
      for (int m = 1; m < members; ++m) {
        lo = std::min(lo, memberRange[2 * m]);
        hi = std::max(hi, memberRange[2 * m + 1]);
      }
      if (distributed) {
        lo = -maxAcrossRanks(-lo);
        hi = maxAcrossRanks(hi);
      }
      if (lo > 0.0) contraction = 12.0 * wMax * std::max(1.0, hi) / (timeCoeff * lo);
    }
    double tol[3];
    bool active[3];
    int its[3] = {0, 0, 0};
    bool inYLocal[3] = {false, false, false};
    bool conv[3] = {true, true, true};
    for (int c = 0; c < 3; ++c) {
      const double bnorm = std::sqrt(sumOfPartials(teamPartial_[c][0]));
      tol[c] = momentumTolerance_ * (bnorm > 0.0 ? bnorm : 1.0);
      active[c] = !unknownList_[c].empty();
    }
    for (int sweep = 0; active[0] || active[1] || active[2]; ++sweep) {
      const int parity = 1 + (sweep & 1);  // partial sums alternate: a member may be one sweep ahead
      for (int c = 0; c < 3; ++c) {
        if (!active[c]) continue;
        Field& x = inYLocal[c] ? precY_[c] : u_[c];
        Field& y = inYLocal[c] ? u_[c] : precY_[c];
        const auto& pts = x.points();
        jacobiSweepRows(x, y, rhs_[c].data().data(), jacobiRows_[c].data(), unknownList_[c].data(),
                        unknownLineStart_[c].data(), mu_, slab.lineBegin(pts), slab.lineEnd(pts),
                        teamPartial_[c][parity].data());
      }
      if (distributed) {  // (the neighbour ranks' ghosts before the boundary conditions, as a full fill)
        std::vector<Field*> swept;
        for (int c = 0; c < 3; ++c)
          if (active[c]) swept.push_back(inYLocal[c] ? &u_[c] : &precY_[c]);
        parallel::fillGhosts(swept, *decomposition_);
      }
      for (int c = 0; c < 3; ++c) {
        if (!active[c]) continue;
        Field& y = inYLocal[c] ? u_[c] : precY_[c];
        const auto& pts = y.points();
        fillVelocityStencilGhostsSlab(y, c, bc_, slab.k0, slab.planeEnd(pts), slab.first, slab.last);
      }
      barrier.wait();
      for (int c = 0; c < 3; ++c) {
        if (!active[c]) continue;
        // Residual of x (before this sweep's update): converged -> keep x, as solveHelmholtz.
        const double rnorm = std::sqrt(sumOfPartials(teamPartial_[c][parity]));
        if (rnorm <= tol[c]) {
          active[c] = false;
        } else if (its[c] >= kMaxSweeps) {
          active[c] = false;
          conv[c] = false;
        } else {
          ++its[c];
          inYLocal[c] = !inYLocal[c];
          if (2.0 * contraction * rnorm <= tol[c]) active[c] = false;  // the new iterate meets tol
        }
      }
    }
    // guessError_ <- predicted velocity minus its guess (unconverged components: after BiCGStab).
    for (int c = 0; c < 3; ++c) {
      if (!conv[c]) continue;
      const double* X = (inYLocal[c] ? precY_[c] : u_[c]).data().data();
      double* G = guessError_[c].data().data();
      const std::uint8_t* M = unknown_[c].data();
      const auto [b, e] = flatRange(u_[c]);
      for (std::size_t q = b; q < e; ++q) G[q] = M[q] ? X[q] - G[q] : 0.0;
    }
    if (slab.first)
      for (int c = 0; c < 3; ++c) {
        iterations[c] = its[c];
        converged[c] = conv[c];
        inY[c] = inYLocal[c];
      }
  };
  runTeam(team, member);  // (a team of one: no region, core/parallel.hpp)
  momentumTeam_.record(team, TeamTuner::now() - started);
  for (int c = 0; c < 3; ++c) {
    if (inY[c]) u_[c].data().swap(precY_[c].data());
    stats_.momentumIterations += iterations[c];
    if (converged[c]) continue;
    // Jacobi stalled: BiCGStab from the current iterate (solveHelmholtz), then the guess error.
    stats_.momentumIterations += solveHelmholtz(c, dt, g0, false);
    const double* X = u_[c].data().data();
    double* G = guessError_[c].data().data();
    const std::uint8_t* M = unknown_[c].data();
    for (std::size_t q = 0; q < u_[c].data().size(); ++q) G[q] = M[q] ? X[q] - G[q] : 0.0;
  }
  // The velocity ghosts beyond the stencil's are filled by project() (after the correction).
  return true;
}

}  // namespace gf::fluid
