// Flux-corrected transport of the phase fractions (vof/vof.hpp, docs/vof.md).
//
// Seed 002 eq. 2 (line 316): d(eps alpha_i)/dt + div(eps alpha_i u) - div(u_c alpha_i (1 - alpha_i)) = 0.
// With phi = eps_f u_f the superficial face velocity, one step of length dt is, per cell,
//   (eps alpha_i)* = eps alpha_i - dt div F_i,  F_i = phi alpha_i,up + C_f A_i   (Zalesak 1979)
// where A_i = phi 0.5 (1 - c)(alpha_down - alpha_up) + compression is the correction beyond
// upwind, C_f in [0, 1] Zalesak's face factor, and the corrections of the phases are then made to
// sum to zero on every face (MULES::limitSum). Finally alpha_i = (eps alpha_i)* / sum_j (eps alpha_j)*.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/parallel.hpp"
#include "vof/kernels.hpp"
#include "vof/vof.hpp"

namespace gf::vof {

namespace {

/// body(i, j, k) over the cells [lo, hi) per axis, threaded over the (j, k) lines.
template <class Body>
void forCells(std::array<int, 3> lo, std::array<int, 3> hi, Body&& body) {
  const int nj = hi[1] - lo[1], nk = hi[2] - lo[2];
  if (nj <= 0 || nk <= 0 || hi[0] <= lo[0]) return;
  gf::parallelFor(static_cast<std::int64_t>(nj) * nk, [&](std::int64_t l) {
    const int j = lo[1] + static_cast<int>(l % nj), k = lo[2] + static_cast<int>(l / nj);
    for (int i = lo[0]; i < hi[0]; ++i) body(i, j, k);
  });
}

double spacing(const CartesianGrid& g, int a) { return a == 0 ? g.spacing.x : (a == 1 ? g.spacing.y : g.spacing.z); }

/// (i, j, k) moved by d along axis a.
std::array<int, 3> shifted(int i, int j, int k, int a, int d) {
  std::array<int, 3> c{i, j, k};
  c[static_cast<std::size_t>(a)] += d;
  return c;
}

double at(const Field& f, const std::array<int, 3>& c) { return f(c[0], c[1], c[2]); }

}  // namespace

void fillCellGhosts(Field& f, const Sides& sides) {
  const auto& pts = f.points();
  const int g = f.grid().ghosts;
  auto& d = f.data();
  for (int a = 0; a < 3; ++a) {
    const int n = pts[static_cast<std::size_t>(a)];
    const std::ptrdiff_t s = f.stride(a);
    const int b = (a + 1) % 3, c = (a + 2) % 3;  // the other two axes, whole extent with ghosts
    const int nb = pts[static_cast<std::size_t>(b)], nc = pts[static_cast<std::size_t>(c)];
    for (int side = 0; side < 2; ++side) {
      const SideType t = sides.at(a, side);
      if (t == SideType::Shared) continue;
      for (int q = -g; q < nc + g; ++q)
        for (int p = -g; p < nb + g; ++p) {
          std::array<int, 3> base{0, 0, 0};
          base[static_cast<std::size_t>(b)] = p;
          base[static_cast<std::size_t>(c)] = q;
          const auto origin = static_cast<std::ptrdiff_t>(f.index(base[0], base[1], base[2]));  // index along a = 0
          for (int l = 1; l <= g; ++l) {
            // ghost index along a, and the interior point it copies
            const int ghost = side == 0 ? -l : n - 1 + l;
            int from;
            if (t == SideType::Periodic) from = side == 0 ? n - l : l - 1;
            else if (t == SideType::Open) from = side == 0 ? 0 : n - 1;  // the boundary cell, repeated
            else from = side == 0 ? std::min(l - 1, n - 1) : std::max(n - l, 0);  // mirror: zero normal gradient
            d[static_cast<std::size_t>(origin + ghost * s)] = d[static_cast<std::size_t>(origin + from * s)];
          }
        }
    }
  }
}

GhostFill singleBoxFill(const Sides& sides) {
  return [sides](const std::vector<Field*>& fields) {
    for (Field* f : fields) fillCellGhosts(*f, sides);
  };
}

PhaseTransport::PhaseTransport(const CartesianGrid& box, int phases) : box_(box), phases_(phases) {
  if (phases < 2) throw std::invalid_argument("vof: at least two phases");
  if (box.ghosts < 2) throw std::invalid_argument("vof: the transport needs two ghost layers");
  epsOld_ = Field(box);
  epsStar_ = Field(box);
  for (int i = 0; i < phases; ++i) {
    for (int a = 0; a < 3; ++a) {
      const auto st = static_cast<Staggering>(a + 1);
      low_.emplace_back(box, st);
      anti_.emplace_back(box, st);
      gradient_.emplace_back(box);
    }
    qLow_.emplace_back(box);
    rPlus_.emplace_back(box, Staggering::Cell, 1.0);
    rMinus_.emplace_back(box, Staggering::Cell, 1.0);
  }
}

std::vector<Field*> PhaseTransport::limiterFields() {
  std::vector<Field*> out;
  for (int i = 0; i < phases_; ++i) {
    out.push_back(&rPlus_[static_cast<std::size_t>(i)]);
    out.push_back(&rMinus_[static_cast<std::size_t>(i)]);
  }
  return out;
}

void PhaseTransport::computeFluxes(const std::vector<Field>& alpha, const Field& eps, const std::array<const Field*, 3>& flux,
                                   double dt, const Sides& sides, const TransportSettings& settings) {
  if (static_cast<int>(alpha.size()) != phases_) throw std::invalid_argument("vof: phase count differs from the work arrays'");
  const int N = phases_;
  const auto& n = box_.cells;
  const double h[3] = {spacing(box_, 0), spacing(box_, 1), spacing(box_, 2)};
  // The loops address every field by the flat index of the box's layout.
  if (eps.extent() != epsOld_.extent()) throw std::invalid_argument("vof: the void fraction is not on the box's grid");
  for (const Field& al : alpha)
    if (al.extent() != epsOld_.extent()) throw std::invalid_argument("vof: a phase fraction is not on the box's grid");
  for (int a = 0; a < 3; ++a)
    if (flux[static_cast<std::size_t>(a)]->extent() != anti_[static_cast<std::size_t>(a)].extent() ||
        flux[static_cast<std::size_t>(a)]->staggering() != anti_[static_cast<std::size_t>(a)].staggering())
      throw std::invalid_argument("vof: a face flux is not a face field of the box's grid");
  dt_ = dt;
  epsOld_.data() = eps.data();

  // Cell-centred gradients of every phase on the cells -1..n (central differences; the ghosts
  // -2 and n+1 are read): the face normals of the compression need them on both sides of a face.
  if (settings.compression > 0.0) {
    for (int i = 0; i < N; ++i)
      for (int a = 0; a < 3; ++a) {
        const Field& al = alpha[static_cast<std::size_t>(i)];
        Field& gr = gradient_[static_cast<std::size_t>(3 * i + a)];
        const double inv2h = 0.5 / h[a];
        const double* av = al.data().data();
        const std::ptrdiff_t cs = al.stride(a);
        forCells({-1, -1, -1}, {n[0] + 1, n[1] + 1, n[2] + 1}, [&](int x, int y, int z) {
          const auto c = static_cast<std::ptrdiff_t>(al.index(x, y, z));
          gr.data()[static_cast<std::size_t>(c)] = (av[c + cs] - av[c - cs]) * inv2h;
        });
      }
  }
  const double delta = 1e-8 / std::cbrt(box_.cellVolume());  // OpenFOAM's deltaN = 1e-8 / (mean cell size)

  // Face fluxes: faces 0..n along a (between cells f-1 and f), cells 0..n-1 along the other axes.
  for (int a = 0; a < 3; ++a) {
    const Field& phi = *flux[static_cast<std::size_t>(a)];
    std::array<int, 3> hi{n[0], n[1], n[2]};
    hi[static_cast<std::size_t>(a)] += 1;
    const bool wallLow = sides.at(a, 0) == SideType::Wall, wallHigh = sides.at(a, 1) == SideType::Wall;
    const bool openLow = sides.at(a, 0) == SideType::Open, openHigh = sides.at(a, 1) == SideType::Open;
    for (int s = 0; s < 2; ++s) {
      const auto& in = sides.inflow[static_cast<std::size_t>(2 * a + s)];
      if (in.empty()) continue;
      double sum = 0.0;
      for (double v : in) sum += v;
      if (static_cast<int>(in.size()) != N || std::abs(sum - 1.0) > 1e-12)
        throw std::invalid_argument("vof: the inflow fractions of a side must be one per phase and sum to 1");
    }
    const int na = n[static_cast<std::size_t>(a)];
    const std::ptrdiff_t cs = eps.stride(a);
    forCells({0, 0, 0}, hi, [&](int x, int y, int z) {
      const std::size_t iN = eps.index(x, y, z), iP = iN - static_cast<std::size_t>(cs);  // cells f and f-1
      const std::size_t iF = phi.index(x, y, z);  // the face (every face field of axis a: same layout)
      const int f = a == 0 ? x : (a == 1 ? y : z);
      const bool wall = (f == 0 && wallLow) || (f == na && wallHigh);
      const double ph = wall ? 0.0 : phi.data()[iF];
      const std::size_t iUp = ph >= 0.0 ? iP : iN, iDown = ph >= 0.0 ? iN : iP;
      const double courant = std::abs(ph) * dt / (std::max(eps.data()[iUp], 1e-12) * h[a]);
      const int openSide = f == 0 && openLow ? 0 : (f == na && openHigh ? 1 : -1);
      if (openSide >= 0) {  // an inlet or outlet face: upwind, no correction
        const auto& in = sides.inflow[static_cast<std::size_t>(2 * a + openSide)];
        const bool inward = openSide == 0 ? ph > 0.0 : ph < 0.0;
        for (int i = 0; i < N; ++i) {
          const double up = inward && !in.empty() ? in[static_cast<std::size_t>(i)]
                                                  : alpha[static_cast<std::size_t>(i)].data()[iUp];
          low_[static_cast<std::size_t>(3 * i + a)].data()[iF] = ph * up;
          anti_[static_cast<std::size_t>(3 * i + a)].data()[iF] = 0.0;
        }
        return;
      }
      for (int i = 0; i < N; ++i) {
        const double* al = alpha[static_cast<std::size_t>(i)].data().data();
        low_[static_cast<std::size_t>(3 * i + a)].data()[iF] = ph * al[iUp];
        anti_[static_cast<std::size_t>(3 * i + a)].data()[iF] =
            settings.highOrder ? ph * kernels::laxWendroffIncrement(al[iUp], al[iDown], courant) : 0.0;
      }
      if (settings.compression > 0.0 && ph != 0.0) {
        const double phic = settings.compression * std::abs(ph);  // C |phi_f|: u_c of seed 002 eq. 2
        for (int i = 0; i < N; ++i)
          for (int j = i + 1; j < N; ++j) {
            const double* ai = alpha[static_cast<std::size_t>(i)].data().data();
            const double* aj = alpha[static_cast<std::size_t>(j)].data().data();
            double g[3];
            for (int b = 0; b < 3; ++b) {
              const double* gi = gradient_[static_cast<std::size_t>(3 * i + b)].data().data();
              const double* gj = gradient_[static_cast<std::size_t>(3 * j + b)].data().data();
              const double gP = aj[iP] * gi[iP] - ai[iP] * gj[iP];
              const double gN = aj[iN] * gi[iN] - ai[iN] * gj[iN];
              g[b] = 0.5 * (gP + gN);
            }
            const double phiR = phic * kernels::pairNormal(g[0], g[1], g[2], a, delta);
            const double c = kernels::pairCompressionFlux(phiR, ai[iP], ai[iN], aj[iP], aj[iN]);
            anti_[static_cast<std::size_t>(3 * i + a)].data()[iF] += c;
            anti_[static_cast<std::size_t>(3 * j + a)].data()[iF] -= c;
          }
      }
    });
  }

  // Upwind solution, bounds and Zalesak's R+ / R- of the box's cells.
  // Flat-index strides: cells along each axis, and faces along their own axis (every face field of
  // an axis has the layout of flux[a]).
  std::ptrdiff_t cellStride[3], faceStride[3];
  for (int a = 0; a < 3; ++a) {
    cellStride[a] = eps.stride(a);
    faceStride[a] = flux[static_cast<std::size_t>(a)]->stride(a);
  }
  forCells({0, 0, 0}, {n[0], n[1], n[2]}, [&](int x, int y, int z) {
    const std::size_t c = eps.index(x, y, z);
    std::size_t fl[3];  // the cell's lower face along each axis
    double divPhi = 0.0;
    for (int a = 0; a < 3; ++a) {
      const Field& phi = *flux[static_cast<std::size_t>(a)];
      fl[a] = phi.index(x, y, z);
      const int f = a == 0 ? x : (a == 1 ? y : z);
      const double lower = (f == 0 && sides.at(a, 0) == SideType::Wall) ? 0.0 : phi.data()[fl[a]];
      const double upper = (f == n[static_cast<std::size_t>(a)] - 1 && sides.at(a, 1) == SideType::Wall)
                               ? 0.0 : phi.data()[fl[a] + static_cast<std::size_t>(faceStride[a])];
      divPhi += (upper - lower) / h[a];
    }
    const double e = eps.data()[c];
    const double epsStar = e - dt * divPhi;  // seed 002 eq. 5 (line 326), discretely
    epsStar_.data()[c] = epsStar;
    for (int i = 0; i < N; ++i) {
      const double* al = alpha[static_cast<std::size_t>(i)].data().data();
      double divLow = 0.0, pIn = 0.0, pOut = 0.0;
      double lo = al[c], hi = lo;
      for (int a = 0; a < 3; ++a) {
        const double* L = low_[static_cast<std::size_t>(3 * i + a)].data().data();
        const double* A = anti_[static_cast<std::size_t>(3 * i + a)].data().data();
        const std::size_t up = fl[a] + static_cast<std::size_t>(faceStride[a]);
        divLow += (L[up] - L[fl[a]]) / h[a];
        const double vm = al[c - static_cast<std::size_t>(cellStride[a])], vp = al[c + static_cast<std::size_t>(cellStride[a])];
        lo = std::min({lo, vm, vp});
        hi = std::max({hi, vm, vp});
        const double aLow = A[fl[a]], aHigh = A[up];  // along +a
        pIn += (std::max(aLow, 0.0) + std::max(-aHigh, 0.0)) * dt / h[a];
        pOut += (std::max(-aLow, 0.0) + std::max(aHigh, 0.0)) * dt / h[a];
      }
      const double q = e * al[c] - dt * divLow;
      qLow_[static_cast<std::size_t>(i)].data()[c] = q;
      lo = std::max(lo, 0.0);  // the physical bounds as well as the local ones (MULES' psiMin, psiMax)
      hi = std::min(hi, 1.0);
      rPlus_[static_cast<std::size_t>(i)].data()[c] = kernels::zalesakRatio(epsStar * hi - q, pIn);
      rMinus_[static_cast<std::size_t>(i)].data()[c] = kernels::zalesakRatio(q - epsStar * lo, pOut);
    }
  });
}

void PhaseTransport::applyLimitedFluxes(std::vector<Field>& alpha) {
  const int N = phases_;
  const auto& n = box_.cells;
  const double h[3] = {spacing(box_, 0), spacing(box_, 1), spacing(box_, 2)};
  const double dt = dt_;
  constexpr int kMaxPhases = 16;
  if (N > kMaxPhases) throw std::invalid_argument("vof: at most 16 phases");

  // Limited fluxes on every face of the box (anti_ then holds the whole flux F_i).
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> hi{n[0], n[1], n[2]};
    hi[static_cast<std::size_t>(a)] += 1;
    const std::ptrdiff_t cs = epsOld_.stride(a);
    forCells({0, 0, 0}, hi, [&](int x, int y, int z) {
      const std::size_t iN = epsOld_.index(x, y, z), iP = iN - static_cast<std::size_t>(cs);
      const std::size_t iF = anti_[static_cast<std::size_t>(a)].index(x, y, z);
      double corr[kMaxPhases];
      for (int i = 0; i < N; ++i) {
        const double A = anti_[static_cast<std::size_t>(3 * i + a)].data()[iF];
        const double* rp = rPlus_[static_cast<std::size_t>(i)].data().data();
        const double* rm = rMinus_[static_cast<std::size_t>(i)].data().data();
        corr[i] = A * kernels::faceFactor(A, rp[iP], rm[iP], rp[iN], rm[iN]);
      }
      kernels::limitSum(corr, N);
      for (int i = 0; i < N; ++i)
        anti_[static_cast<std::size_t>(3 * i + a)].data()[iF] = low_[static_cast<std::size_t>(3 * i + a)].data()[iF] + corr[i];
    });
  }

  // eps alpha_i after the step, and the renormalisation by their sum (= eps* to round-off).
  forCells({0, 0, 0}, {n[0], n[1], n[2]}, [&](int x, int y, int z) {
    double q[kMaxPhases];
    double sum = 0.0;
    const std::size_t c = epsOld_.index(x, y, z);
    for (int i = 0; i < N; ++i) {
      double d = 0.0;
      for (int a = 0; a < 3; ++a) {
        const Field& F = anti_[static_cast<std::size_t>(3 * i + a)];
        const std::size_t lower = F.index(x, y, z);
        d += (F.data()[lower + static_cast<std::size_t>(F.stride(a))] - F.data()[lower]) / h[a];
      }
      q[i] = epsOld_.data()[c] * alpha[static_cast<std::size_t>(i)].data()[c] - dt * d;
      sum += q[i];
    }
    if (!(sum > 0.0)) return;  // no fluid volume left in the cell: keep its fractions
    for (int i = 0; i < N; ++i) alpha[static_cast<std::size_t>(i)].data()[c] = q[i] / sum;
  });
}

double PhaseTransport::boundaryOutflow(int phase, int axis, int s, const Sides& sides) const {
  double local = 0.0;
  if (sides.at(axis, s) != SideType::Shared) {
    const Field& F = anti_[static_cast<std::size_t>(3 * phase + axis)];  // the step's whole fluxes
    const auto& n = box_.cells;
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    const double area = box_.cellVolume() / spacing(box_, axis);
    for (int q = 0; q < n[static_cast<std::size_t>(c)]; ++q)
      for (int p = 0; p < n[static_cast<std::size_t>(b)]; ++p) {
        std::array<int, 3> idx{0, 0, 0};
        idx[static_cast<std::size_t>(axis)] = s == 0 ? 0 : n[static_cast<std::size_t>(axis)];
        idx[static_cast<std::size_t>(b)] = p;
        idx[static_cast<std::size_t>(c)] = q;
        local += F(idx[0], idx[1], idx[2]) * area;
      }
    if (s == 0) local = -local;  // along +axis is into the domain at the lower side
  }
  return sumAcrossRanks(local);
}

void advance(PhaseTransport& work, std::vector<Field>& alpha, const Field& eps, const std::array<const Field*, 3>& flux,
             double dt, const Sides& sides, const TransportSettings& settings, const GhostFill& fill) {
  std::vector<Field*> a;
  for (auto& f : alpha) a.push_back(&f);
  fill(a);
  work.computeFluxes(alpha, eps, flux, dt, sides, settings);
  fill(work.limiterFields());
  work.applyLimitedFluxes(alpha);
  fill(a);
}

int advanceSubcycled(PhaseTransport& work, std::vector<Field>& alpha, const Field& eps, const std::array<const Field*, 3>& flux,
                     double dt, const Sides& sides, const TransportSettings& settings, const GhostFill& fill,
                     double courantLimit, const std::function<void(double substep)>& afterSubstep) {
  if (!(courantLimit > 0.0 && courantLimit <= 1.0)) throw std::invalid_argument("vof: the substeps' Courant limit must lie in (0, 1]");
  // eps at the end of the step (seed 002 eq. 5), for the Courant number where the bed fills up
  const CartesianGrid& g = eps.grid();
  const auto& n = g.cells;
  Field epsEnd(eps);
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        double divPhi = 0.0;
        for (int a = 0; a < 3; ++a) {
          const Field& phi = *flux[static_cast<std::size_t>(a)];
          divPhi += (at(phi, shifted(x, y, z, a, 1)) - phi(x, y, z)) / spacing(g, a);
        }
        epsEnd(x, y, z) = eps(x, y, z) - dt * divPhi;
      }
  const double courant = std::max(maxCourant(eps, flux, dt), maxCourant(epsEnd, flux, dt));
  const int substeps = std::max(1, static_cast<int>(std::ceil(courant / courantLimit)));
  const double h = dt / substeps;
  Field e(eps);
  for (int k = 0; k < substeps; ++k) {
    advance(work, alpha, e, flux, h, sides, settings, fill);
    if (afterSubstep) afterSubstep(h);
    if (k + 1 < substeps) {
      e.data() = work.transportedVoidFraction().data();
      fill({&e});
    }
  }
  return substeps;
}

double maxCourant(const Field& eps, const std::array<const Field*, 3>& flux, double dt) {
  const CartesianGrid& g = eps.grid();
  const auto& n = g.cells;
  const double h[3] = {spacing(g, 0), spacing(g, 1), spacing(g, 2)};
  double m = 0.0;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        double out = 0.0;
        for (int a = 0; a < 3; ++a) {
          const Field& phi = *flux[static_cast<std::size_t>(a)];
          out += (std::max(at(phi, shifted(x, y, z, a, 1)), 0.0) + std::max(-phi(x, y, z), 0.0)) * dt / h[a];
        }
        m = std::max(m, out / std::max(eps(x, y, z), 1e-12));
      }
  return maxAcrossRanks(m);
}

double phaseVolume(const Field& alpha, const Field& eps, const SumPolicy& policy) {
  const auto& n = alpha.grid().cells;
  const std::int64_t lines = static_cast<std::int64_t>(n[1]) * n[2];
  const double v = alpha.grid().cellVolume();
  return globalSum(lines, policy, [&](std::int64_t l) {
    const int y = static_cast<int>(l % n[1]), z = static_cast<int>(l / n[1]);
    double s = 0.0;
    for (int x = 0; x < n[0]; ++x) s += eps(x, y, z) * alpha(x, y, z);
    return s * v;
  });
}

double maxSumError(const std::vector<Field>& alpha) {
  const auto& n = alpha.front().grid().cells;
  double m = 0.0;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        double s = 0.0;
        for (const Field& a : alpha) s += a(x, y, z);
        m = std::max(m, std::abs(s - 1.0));
      }
  return maxAcrossRanks(m);
}

std::array<double, 2> fractionRange(const Field& alpha) {
  const auto& n = alpha.grid().cells;
  double lo = alpha(0, 0, 0), hi = lo;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        lo = std::min(lo, alpha(x, y, z));
        hi = std::max(hi, alpha(x, y, z));
      }
  return {-maxAcrossRanks(-lo), maxAcrossRanks(hi)};
}

void mixtureField(const std::vector<Field>& alpha, const std::vector<double>& value, Field& out) {
  const int N = static_cast<int>(alpha.size());
  if (static_cast<int>(value.size()) != N) throw std::invalid_argument("vof: one value per phase");
  auto& o = out.data();
  gf::parallelFor(static_cast<std::int64_t>(o.size()), [&](std::int64_t p) {
    double s = 0.0;  // seed 002 eqs. 3-4 (lines 320-322)
    for (int i = 0; i < N; ++i) s += alpha[static_cast<std::size_t>(i)].data()[static_cast<std::size_t>(p)] * value[static_cast<std::size_t>(i)];
    o[static_cast<std::size_t>(p)] = s;
  });
}

}  // namespace gf::vof
