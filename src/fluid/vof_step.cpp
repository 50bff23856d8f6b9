// The fluid step with several immiscible fluids (fluid.vof; docs/vof.md): mixture density and
// viscosity from the phase fractions (seed 002 eqs. 3-4, lines 320-322), the momentum equation
// with the modified pressure p* = p - rho_f g.x (seed 002 eq. 6, line 328), the projection with
// 1/rho_f (fluid/variable_density.hpp), and the phase transport (src/vof, sub-cycled).
//
// Order of a step (as OpenFOAM's interFoam): the fractions first, moved by the face fluxes of the
// last projection (alpha^n -> alpha^{n+1}, rho^n -> rho^{n+1}); the transport's upwind phase
// fluxes F^L_i give the mass flux M = sum_i rho_i F^L_i (mean over the substeps). Then the
// predictor (first order in time, explicit convection and viscous stress, implicit drag diagonal)
// at every momentum unknown face f of component c, with a = eps_f (model A) or 1 (model B), on the
// control volume of the face (half of each neighbour cell):
//
//   (m^{n+1}_f / dt + K_f) u*  =  m^n_f u^n / dt - sum_faces M_cv u^n_upwind
//        + div(eps mu_f (grad u + grad u^T))_c - a d p*/dx_c - a (g.x)_f d rho^{n+1}/dx_c
//        + (eps_f - a) rho_f g_c + a drive + F_f + K_f u_p,f
//
// m^n_f = (rho^n_L eps^n_L + rho^n_R eps^n_R)/2; the control volume's mass fluxes M_cv are the
// means of its two cells' M, and its new mass m^{n+1}_f = m^n_f - dt div M_cv is its own balance
// of them. The momentum thus moves with the mass that moves (Rudman 1998, Int. J. Numer. Meth.
// Fluids 28): a light cell that takes in heavy fluid takes in its momentum too, and what leaves a
// control volume carries its own velocity, so (m^n - dt M_out) u^n >= 0 keeps u* bounded where the
// volume empties of water (the fractions' own high-order fluxes, averaged onto a control volume,
// do not guarantee that: a version with them ran away in the dam break). m^{n+1}_f differs from the
// new fractions' (rho^{n+1} eps)_f, which the projection takes, by the transport's limited
// corrections.
//
// The buoyancy -(g.x)_f (rho_R - rho_L)/h (fluid::hydrostaticFaceForce) carries the same face
// coefficient a as the pressure gradient, so a column at rest with any density jump has a
// discrete p* that cancels it face by face ("balanced force"): u* = u^n = 0, and the projection
// of a zero field stays zero. rho_f = (rho_L + rho_R)/2 (fluid::faceDensity) in the buoyancy and
// the projection alike. Model A: the eps rho g of the single-fluid equation is part of the
// buoyancy term (-eps grad p + eps rho g = -eps grad p* - eps (g.x) grad rho); model B keeps
// (eps - 1) rho g.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <omp.h>

#include "fluid/loops.hpp"
#include "fluid/solver.hpp"
#include "fluid/variable_density.hpp"
#include "core/reduction.hpp"
#include "parallel/halo.hpp"
#include "parallel/reductions.hpp"

namespace gf::fluid {

namespace {
/// The face fluxes eps_f u_f of the velocity component u (faces of axis a; eps_f the mean of the
/// cells on either side, E laid out as `cells`) into phi, or (difference) minus what phi held.
void faceFluxes(const Field& u, const double* E, const Field& cells, int a, Field& phi, bool difference) {
  const auto& pts = u.points();
  const std::ptrdiff_t se = cells.stride(a);
  for (int k = 0; k < pts[2]; ++k)
    for (int j = 0; j < pts[1]; ++j)
      for (int i = 0; i < pts[0]; ++i) {
        const std::size_t cc = cells.index(i, j, k);
        const double flux = 0.5 * (E[cc] + E[cc - se]) * u(i, j, k);
        phi(i, j, k) = difference ? flux - phi(i, j, k) : flux;
      }
}
}  // namespace

void Solver::readVof(Params& fluid) {
  if (!fluid.documenting() && !fluid.has("vof")) {
    for (int s = 0; s < 6; ++s)
      if (!bc_.side[s].phase.empty())
        fluid.section({"boundaries"}).section({sideName(s)}).fail("phase", "'" + bc_.side[s].phase + "'",
                                                                 "no phase: the case has no fluid.vof");
    return;
  }
  Params v = fluid.section({"vof", "-",
                            "several immiscible fluids by volume of fluid (docs/vof.md): phase fractions moved by the "
                            "fluid's fluxes, mixture density and viscosity, modified pressure p* = p - rho g.x"});
  std::vector<Params> phaseList =
      v.list({"phases", "-", "the fluids, at least two: {name, density, viscosity}; the first fills what no region claims"});
  for (Params& ph : phaseList) {
    VofPhase p;
    p.name = ph.text({"name", "-", "phase name (output field alpha_<name>, monitors)"}, "");
    p.density = ph.real({"density", "kg/m^3", "density of the phase", Range::positive()}, 1000.0);
    p.viscosity = ph.real({"viscosity", "Pa s", "dynamic viscosity of the phase", Range::nonNegative()}, 1e-3);
    if (ph.documenting()) continue;
    if (p.name.empty()) ph.fail("name", "an empty name", "a phase name");
    for (const VofPhase& q : phases_)
      if (q.name == p.name) ph.fail("name", "'" + p.name + "' used twice", "a unique phase name");
    phases_.push_back(p);
  }
  auto names = [&]() {
    std::string s;
    for (const VofPhase& q : phases_) s += (s.empty() ? "" : ", ") + q.name;
    return s;
  };
  if (!v.documenting() && phases_.size() < 2)
    v.fail("phases", fmt::format("{} phase(s)", phases_.size()), "at least two phases");
  struct Region {
    int phase;
    Vec3 lo, hi;
  };
  std::vector<Region> regions;
  for (Params& r : v.list({"regions", "-", "initial boxes of phases (later boxes overwrite earlier ones)"})) {
    const std::string name = r.text({"phase", "-", "name of the phase that fills the box"}, "");
    const Vec3 lo = r.vec3({"min", "m", "box lower corner"}, Vec3{});
    const Vec3 hi = r.vec3({"max", "m", "box upper corner"}, Vec3{});
    if (r.documenting()) continue;
    const int idx = phaseIndex(name);
    if (idx < 0) r.fail("phase", "'" + name + "'", "one of the phases: " + names());
    regions.push_back({idx, lo, hi});
  }
  vofSettings_.compression = v.real(
      {"compression", "-", "C of Rusche's compression velocity u_c = C |phi_f| n (0: no interface compression)",
       Range::nonNegative()},
      1.0);
  vofCourant_ = v.real({"courant", "-",
                        "largest outflow Courant number of a phase-transport substep (the fluid step is split into "
                        "as many equal substeps as this needs)",
                        Range{0.0, 1.0, false, true}},
                       0.5);
  const std::string inflow =
      v.text({"inflow_phase", "-",
              "phase entering through inlets, and through outlets where the flow turns inwards (default: the first)"},
             "");
  if (v.documenting()) return;
  vofInflowPhase_ = 0;
  if (!inflow.empty()) {
    vofInflowPhase_ = phaseIndex(inflow);
    if (vofInflowPhase_ < 0) v.fail("inflow_phase", "'" + inflow + "'", "one of the phases: " + names());
  }
  // An inlet per phase: boundaries.<side>.phase names what enters through that side.
  for (int s = 0; s < 6; ++s) {
    vofSidePhase_[static_cast<std::size_t>(s)] = vofInflowPhase_;
    const std::string& name = bc_.side[s].phase;
    if (name.empty()) continue;
    Params side = fluid.section({"boundaries"}).section({sideName(s)});
    const BoundaryType t = bc_.domainSide(s / 2, s % 2);
    if (!(isOutlet(t) || t == BoundaryType::Inlet))
      side.fail("phase", "'" + name + "' on a closed or periodic side", "no phase (only inlets and outlets let a phase in)");
    const int idx = phaseIndex(name);
    if (idx < 0) side.fail("phase", "'" + name + "'", "one of the phases of fluid.vof: " + names());
    vofSidePhase_[static_cast<std::size_t>(s)] = idx;
  }
  if (correctors_ != 1)
    fluid.fail("correctors", fmt::format("{} with fluid.vof", correctors_), "1 (the VOF step has one projection)");
  if (driveMode_ == DrivingMode::FlowRate)
    fluid.section({"driving"}).fail("mode", "flow_rate with fluid.vof", "none or pressure_gradient");
  vof_ = true;
  const int n = static_cast<int>(phases_.size());
  alpha_.assign(static_cast<std::size_t>(n), Field(grid_));
  rhoCell_ = Field(grid_);
  muCell_ = Field(grid_);
  pTotal_ = Field(grid_);
  vofEps_ = Field(grid_, Staggering::Cell, 1.0);
  for (int c = 0; c < 3; ++c) {
    vofFlux_[c] = Field(grid_, static_cast<Staggering>(c + 1));
    massFlux_[c] = Field(grid_, static_cast<Staggering>(c + 1));
  }
  rhoOld_ = Field(grid_);
  transport_ = vof::PhaseTransport(grid_, n);
  phaseOutflow_.assign(static_cast<std::size_t>(n), 0.0);
  phaseOutflowRate_.assign(static_cast<std::size_t>(n), 0.0);
  setPhases([&](const Vec3& x) {
    int phase = 0;
    for (const Region& r : regions)
      if (x.x >= r.lo.x && x.x <= r.hi.x && x.y >= r.lo.y && x.y <= r.hi.y && x.z >= r.lo.z && x.z <= r.hi.z)
        phase = r.phase;
    return phase;
  });
}

int Solver::phaseIndex(const std::string& name) const {
  for (std::size_t i = 0; i < phases_.size(); ++i)
    if (phases_[i].name == name) return static_cast<int>(i);
  return -1;
}

vof::Sides Solver::vofSides() const {
  // The fluid's sides as the transport sees them: shared cuts and periodic wraps as they are,
  // inlets and outlets open (what enters carries the side's phase: boundaries.<side>.phase or
  // fluid.vof.inflow_phase), walls and slip walls closed.
  vof::Sides sides;
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < 2; ++s) {
      const auto k = static_cast<std::size_t>(2 * a + s);
      const BoundaryType t = bc_.at(a, s).type;
      if (bc_.shared(a, s)) sides.side[k] = vof::SideType::Shared;
      else if (t == BoundaryType::Periodic) sides.side[k] = vof::SideType::Periodic;
      else if (isOutlet(t) || t == BoundaryType::Inlet) {
        sides.side[k] = vof::SideType::Open;
        sides.inflow[k].assign(phases_.size(), 0.0);
        if (!phases_.empty()) sides.inflow[k][static_cast<std::size_t>(vofSidePhase_[k])] = 1.0;
      } else sides.side[k] = vof::SideType::Wall;
    }
  return sides;
}

vof::GhostFill Solver::vofGhostFill(const vof::Sides& sides) const {
  return decomposition_->distributed() ? vof::decomposedFill(*decomposition_, sides) : vof::singleBoxFill(sides);
}

void Solver::addBoundaryOutflow(std::vector<double>& outflow, double h, const vof::Sides& sides) const {
  // (every rank the same sides in the same order: boundaryOutflow sums across the ranks)
  const int dims = twoD_ ? 2 : 3;
  for (int a = 0; a < dims; ++a)
    for (int s = 0; s < 2; ++s) {
      const BoundaryType t = bc_.domainSide(a, s);
      if (!(isOutlet(t) || t == BoundaryType::Inlet)) continue;
      for (std::size_t i = 0; i < outflow.size(); ++i)
        outflow[i] += h * transport_.boundaryOutflow(static_cast<int>(i), a, s, sides);
    }
}

void Solver::setPhases(const std::function<int(const Vec3&)>& phaseAt) {
  if (!vof_) throw std::logic_error("Solver::setPhases without fluid.vof");
  for (Field& a : alpha_) std::fill(a.data().begin(), a.data().end(), 0.0);
  for (int k = 0; k < grid_.cells[2]; ++k)
    for (int j = 0; j < grid_.cells[1]; ++j)
      for (int i = 0; i < grid_.cells[0]; ++i) {
        const int p = std::clamp(phaseAt(grid_.cellCentre(i, j, k)), 0, static_cast<int>(alpha_.size()) - 1);
        alpha_[static_cast<std::size_t>(p)](i, j, k) = 1.0;
      }
  const vof::Sides sides = vofSides();
  std::vector<Field*> fields;
  for (Field& a : alpha_) fields.push_back(&a);
  vofGhostFill(sides)(fields);
  updateMixture();
}

void Solver::updateMixture() {
  // rho_f, mu_f (seed 002 eqs. 3-4) over the box, ghosts included, and p = p* + rho g.x.
  std::vector<double> rho, mu;
  for (const VofPhase& p : phases_) {
    rho.push_back(p.density);
    mu.push_back(p.viscosity);
  }
  vof::mixtureField(alpha_, rho, rhoCell_);
  vof::mixtureField(alpha_, mu, muCell_);
  const int g = grid_.ghosts;
  for (int k = -g; k < grid_.cells[2] + g; ++k)
    for (int j = -g; j < grid_.cells[1] + g; ++j)
      for (int i = -g; i < grid_.cells[0] + g; ++i) {
        const std::size_t c = p_.index(i, j, k);
        pTotal_.data()[c] = pressureFromModified(p_.data()[c], rhoCell_.data()[c], dot(gravity_, grid_.cellCentre(i, j, k)));
      }
}

void Solver::predictMomentumVof(double dt) {
  const int dims = twoD_ ? 2 : 3;
  const double* E = coupling_.voidFraction.data().data();
  const double* En = coupling_.voidFractionOld.data().data();
  const double* K = coupling_.dragCoefficient.data().data();
  const double* R = rhoCell_.data().data();  // rho^{n+1}
  const double* R0 = rhoOld_.data().data();  // rho^n
  const double* M = muCell_.data().data();
  const double* P = p_.data().data();
  const bool modelA = model_ == MomentumModel::A;
  // Explicit viscous stress: stable for dt <= min over cells of rho h^2 / (2 dims mu) (the
  // diffusion number 1/2 per direction); the step is refused above it.
  {
    double hmin2 = std::numeric_limits<double>::max();
    for (int d = 0; d < dims; ++d) hmin2 = std::min(hmin2, grid_.spacing[d] * grid_.spacing[d]);
    double nuMax = 0.0;
    for (int k = 0; k < grid_.cells[2]; ++k)
      for (int j = 0; j < grid_.cells[1]; ++j)
        for (int i = 0; i < grid_.cells[0]; ++i) nuMax = std::max(nuMax, muCell_(i, j, k) / rhoCell_(i, j, k));
    nuMax = maxAcrossRanks(nuMax);
    const double limit = nuMax > 0.0 ? hmin2 / (2.0 * dims * nuMax) : std::numeric_limits<double>::max();
    if (dt > limit)
      throw DivergenceError(steps_, time_, "fluid time step", "fluid.vof", Vec3{},
                            fmt::format("dt = {:.3g} s above the explicit viscous limit {:.3g} s of the mixture "
                                        "(h^2 rho / (2 d mu))",
                                        dt, limit));
  }
  for (int c = 0; c < dims; ++c) {
    Field& u = u_[c];
    uOld_[c].data() = u.data();  // u^n (u^{n-1} of the next step)
    const double* U = uOld_[c].data().data();
    const double* F = coupling_.forceDensity[c].data().data();
    const double* Up = coupling_.particleVelocity[c].data().data();
    const auto& pts = u.points();
    const auto& mask = unknown_[c];
    const std::ptrdiff_t se[3] = {p_.stride(0), p_.stride(1), p_.stride(2)};
    const std::ptrdiff_t su[3] = {u.stride(0), u.stride(1), u.stride(2)};
    const double hc = grid_.spacing[c];
    const double gc = gravity_[c];
    const double drive = (driveMode_ != DrivingMode::None && driveAxis_ == c) ? drive_ : 0.0;
    double* Out = u.data().data();
    parallelFor(static_cast<std::int64_t>(pts[1]) * pts[2], [&](std::int64_t line) {
      const int j = static_cast<int>(line % pts[1]), k = static_cast<int>(line / pts[1]);
      for (int i = 0; i < pts[0]; ++i) {
        const std::size_t f = u.index(i, j, k);
        if (!mask[f]) continue;
        const std::size_t cc = p_.index(i, j, k), cm = cc - se[c];
        const double rhoF = faceDensity(R[cm], R[cc]);
        const double epsF = 0.5 * (E[cc] + E[cm]);
        // masses per volume of the face's control volume at n and n + 1
        const double m0 = 0.5 * (R0[cm] * En[cm] + R0[cc] * En[cc]);
        double m1 = 0.0;  // m0 - dt div M of the control volume (below, with the convection)
        const double KF = 0.5 * (K[cc] + K[cm]);
        const double a = modelA ? epsF : 1.0;
        Vec3 x = grid_.cellCentre(i, j, k);
        x[c] -= 0.5 * hc;
        // Convection with the transport's mass fluxes: through the control volume's faces the
        // mean of its two cells' M (at a cell centre along c, on a cell edge across).
        double conv = 0.0;
        for (int d = 0; d < dims; ++d) {
          const Field& Md = massFlux_[d];
          const double* MD = Md.data().data();
          double Mp, Mm;
          if (d == c) {
            const std::size_t g = Md.index(i, j, k);
            Mp = 0.5 * (MD[g] + MD[g + Md.stride(c)]);
            Mm = 0.5 * (MD[g - Md.stride(c)] + MD[g]);
          } else {
            const std::size_t gc = Md.index(i, j, k), gm = gc - Md.stride(c);
            const std::ptrdiff_t sd = Md.stride(d);
            Mp = 0.5 * (MD[gc + sd] + MD[gm + sd]);
            Mm = 0.5 * (MD[gc] + MD[gm]);
          }
          const std::ptrdiff_t s = su[d];
          // upwind: what leaves the control volume carries its own velocity, so the momentum left
          // behind is (m^n - dt M_out) u^n and u* stays bounded where m^{n+1} << m^n (air that
          // a water cell leaves behind); a higher-order face value breaks this at 1000:1
          const double qp = Mp >= 0.0 ? U[f] : U[f + s];
          const double qm = Mm >= 0.0 ? U[f - s] : U[f];
          conv += (Mp * qp - Mm * qm) / grid_.spacing[d];
          m1 -= dt * (Mp - Mm) / grid_.spacing[d];
        }
        m1 += m0;
        // div(eps mu (grad u + grad u^T)) along c: normal stresses at the cell centres, shear
        // stresses at the cell edges (mu and eps the means of the four cells around an edge).
        double visc = 0.0;
        for (int d = 0; d < dims; ++d) {
          if (d == c) {
            const double hi = 2.0 * M[cc] * E[cc] * (U[f + su[c]] - U[f]) / hc;
            const double lo = 2.0 * M[cm] * E[cm] * (U[f] - U[f - su[c]]) / hc;
            visc += (hi - lo) / hc;
            continue;
          }
          const double hd = grid_.spacing[d];
          // u_d at time n (components before c already hold their u*, u^n kept in uOld_)
          const double* V = (d < c ? uOld_[d] : u_[d]).data().data();
          const std::ptrdiff_t vd = u_[d].stride(d);
          const std::size_t idc = u_[d].index(i, j, k), idm = idc - u_[d].stride(c);
          const std::size_t ch = cc + se[d], mh = cm + se[d], cl = cc - se[d], ml = cm - se[d];
          const double muHi = 0.25 * (M[cc] * E[cc] + M[cm] * E[cm] + M[ch] * E[ch] + M[mh] * E[mh]);
          const double muLo = 0.25 * (M[cc] * E[cc] + M[cm] * E[cm] + M[cl] * E[cl] + M[ml] * E[ml]);
          const double tauHi = muHi * ((U[f + su[d]] - U[f]) / hd + (V[idc + vd] - V[idm + vd]) / hc);
          const double tauLo = muLo * ((U[f] - U[f - su[d]]) / hd + (V[idc] - V[idm]) / hc);
          visc += (tauHi - tauLo) / hd;
        }
        double b = m0 * U[f] / dt - conv + visc;
        b -= a * (P[cc] - P[cm]) / hc;
        b += a * hydrostaticFaceForce(dot(gravity_, x), R[cm], R[cc], hc);
        b += (epsF - a) * rhoF * gc + a * drive;
        b += 0.5 * (F[cc] + F[cm]) + 0.5 * (K[cc] * Up[cc] + K[cm] * Up[cm]);
        Out[f] = b / (m1 / dt + KF);
      }
    });
  }
  if (dims == 2) uOld_[2].data() = u_[2].data();
  for (int c = 0; c < 3; ++c) fillVelocityGhosts(u_[c], c, bc_, GhostMode::Full);
}

void Solver::transportPhases(double dt) {
  // The face fluxes eps^n_f u^n of the last projection move the fractions from eps^n: with
  // eps = 1 eps* = eps^n - dt div(phi) is 1 to the pressure solver's tolerance; with particles
  // eps* = 2 eps^n - eps^{n-1}, eps^{n+1} to second order in dt.
  const int dims = twoD_ ? 2 : 3;
  const double* E = coupling_.voidFractionOld.data().data();
  for (int a = 0; a < 3; ++a) {
    Field& phi = vofFlux_[a];
    std::fill(phi.data().begin(), phi.data().end(), 0.0);
    if (a < dims) faceFluxes(u_[a], E, p_, a, phi, false);
  }
  // Inlet faces: the flux of the last projection, which took the inlet velocity at t^n. This
  // step's ghost fill has already set the faces to t^{n+1}'s (a ramp), and to U / eps_f with the
  // new eps (superficial inlets): with the interior's fluxes of t^n those would not balance, and
  // each phase would gain dt (U^{n+1} - U^n) A per step. (A face the fill left at 0, blocked or
  // at rest, stays 0.)
  Boundaries last = bc_;
  last.time = time_;
  for (int a = 0; a < dims; ++a)
    for (int s = 0; s < 2; ++s) {
      const BoundarySide& side = bc_.at(a, s);
      if (side.type != BoundaryType::Inlet) continue;
      Field& phi = vofFlux_[a];
      const auto& pts = phi.points();
      const std::ptrdiff_t se = p_.stride(a);
      int lo[3] = {0, 0, 0}, hi[3] = {pts[0], pts[1], pts[2]};
      lo[a] = s == 0 ? 0 : grid_.cells[a];
      hi[a] = lo[a] + 1;
      for (int k = lo[2]; k < hi[2]; ++k)
        for (int j = lo[1]; j < hi[1]; ++j)
          for (int i = lo[0]; i < hi[0]; ++i) {
            if (u_[a](i, j, k) == 0.0) continue;
            Vec3 x = grid_.cellCentre(i, j, k);
            x[a] -= 0.5 * grid_.spacing[a];
            const double un = inletNormalVelocity(last, a, s, grid_, x);
            const std::size_t cc = p_.index(i, j, k);
            phi(i, j, k) = side.superficial ? un : 0.5 * (E[cc] + E[cc - se]) * un;
          }
    }
  vofEps_.data() = coupling_.voidFractionOld.data();
  const vof::Sides sides = vofSides();
  const vof::GhostFill fill = vofGhostFill(sides);
  fill({&vofEps_});
  const int n = phaseCount();
  std::vector<double> outflow(static_cast<std::size_t>(n), 0.0);
  for (Field& m : massFlux_) std::fill(m.data().begin(), m.data().end(), 0.0);
  auto afterSubstep = [&](double h) {
    // the upwind mass flux sum_i rho_i F^L_i, the mean over the substeps
    for (int a = 0; a < dims; ++a) {
      Field& M = massFlux_[a];
      const auto& pts = M.points();
      for (int k = 0; k < pts[2]; ++k)
        for (int j = 0; j < pts[1]; ++j)
          for (int i = 0; i < pts[0]; ++i) {
            const std::size_t q = M.index(i, j, k);
            double sum = 0.0;
            for (int p = 0; p < n; ++p) sum += phases_[static_cast<std::size_t>(p)].density * transport_.upwindFlux(p, a).data()[q];
            M.data()[q] += (h / dt) * sum;
          }
    }
    addBoundaryOutflow(outflow, h, sides);
  };
  vofSubsteps_ = vof::advanceSubcycled(transport_, alpha_, vofEps_, {&vofFlux_[0], &vofFlux_[1], &vofFlux_[2]}, dt,
                                       sides, vofSettings_, fill, vofCourant_, afterSubstep);
  for (int i = 0; i < n; ++i) {
    phaseOutflow_[static_cast<std::size_t>(i)] += outflow[static_cast<std::size_t>(i)];
    phaseOutflowRate_[static_cast<std::size_t>(i)] = outflow[static_cast<std::size_t>(i)] / dt;
  }
  // Ghosts of the mass fluxes: the neighbours' faces across the cuts, the periodic wraps of this
  // box (the predictor reads the faces of the cells on both sides of a momentum face).
  std::vector<Field*> fields{&massFlux_[0], &massFlux_[1], &massFlux_[2]};
  if (decomposition_->distributed()) parallel::fillGhosts(fields, *decomposition_);
  for (int a = 0; a < 3; ++a) {
    if (!bc_.periodic(a)) continue;
    const int cells = grid_.cells[a], g = grid_.ghosts;
    for (Field* f : fields) {
      const auto& pts = f->points();
      int lo[3] = {-g, -g, -g}, hi[3] = {pts[0] + g, pts[1] + g, pts[2] + g};
      for (int k = lo[2]; k < hi[2]; ++k)
        for (int j = lo[1]; j < hi[1]; ++j)
          for (int i = lo[0]; i < hi[0]; ++i) {
            int idx[3] = {i, j, k};
            const int along = idx[a];
            if (along >= 0 && along < pts[a]) continue;
            idx[a] = ((along % cells) + cells) % cells;  // (period: the cell count)
            (*f)(i, j, k) = (*f)(idx[0], idx[1], idx[2]);
          }
    }
  }
}

void Solver::transportPhasesToProjection(double dt) {
  // With moving particles the transport's fluxes phi^n took the fractions to eps* = eps^n - dt
  // div(phi^n) = 2 eps^n - eps^{n-1}, while the step's continuity equation holds with the
  // coupling's eps^{n+1}: a phase measured with eps^{n+1} would gain or lose alpha (eps^{n+1} - eps*) V
  // in every cell where the particles' motion changes and alpha is not uniform. The projection's
  // fluxes phi^{n+1} = eps^{n+1}_f u^{n+1} meet eps^n - dt div(phi^{n+1}) = eps^{n+1} (to the
  // pressure solver's tolerance), so a second transport with dphi = phi^{n+1} - phi^n takes the
  // contents from eps* on to eps^{n+1}: over the step the fractions move with phi^{n+1}, the
  // conservative flux form is kept, and the phases' volumes measured with eps^{n+1} close with
  // their outflow. No compression (dphi is not a velocity of the interface); the Lax-Wendroff
  // correction and the limiter as in the step, so the bounds hold.
  const int dims = twoD_ ? 2 : 3;
  const double* E = coupling_.voidFraction.data().data();
  for (int a = 0; a < dims; ++a) faceFluxes(u_[a], E, p_, a, vofFlux_[a], true);  // phi^n in, dphi out
  vofEps_.data() = transport_.transportedVoidFraction().data();  // eps* (interior; ghosts below)
  const vof::Sides sides = vofSides();
  const vof::GhostFill fill = vofGhostFill(sides);
  fill({&vofEps_});
  const int n = phaseCount();
  std::vector<double> outflow(static_cast<std::size_t>(n), 0.0);
  auto afterSubstep = [&](double h) { addBoundaryOutflow(outflow, h, sides); };
  vof::TransportSettings settings = vofSettings_;
  settings.compression = 0.0;
  vof::advanceSubcycled(transport_, alpha_, vofEps_, {&vofFlux_[0], &vofFlux_[1], &vofFlux_[2]}, dt, sides, settings,
                        fill, vofCourant_, afterSubstep);
  for (int i = 0; i < n; ++i) {
    phaseOutflow_[static_cast<std::size_t>(i)] += outflow[static_cast<std::size_t>(i)];
    phaseOutflowRate_[static_cast<std::size_t>(i)] += outflow[static_cast<std::size_t>(i)] / dt;
  }
}

void Solver::stepVof(double dt) {
  ScopedPhase timer(timers_, Phase::Fluid);
  const parallel::RankReductionScope ranks(*decomposition_);
  const SerialFluidScope serial(grid_.interiorCellCount() < kSerialCellsBelow);
  // (small grids: the transport's loops, which go through gf::parallelFor, on this thread too)
  struct OneThread {
    int previous = omp_get_max_threads();
    bool on;
    explicit OneThread(bool o) : on(o) {
      if (on) omp_set_num_threads(1);
    }
    ~OneThread() {
      if (on) omp_set_num_threads(previous);
    }
  } oneThread(grid_.interiorCellCount() < kSerialCellsBelow);
  bc_.time = time_ + dt;
  bc_.voidFraction = &coupling_.voidFraction;
  fillAllGhosts();
  bool uniform = true;
  {
    const auto& eps = coupling_.voidFraction.data();
    const auto& epsOld = coupling_.voidFractionOld.data();
    const auto& K = coupling_.dragCoefficient.data();
    for (std::size_t i = 0; i < eps.size() && uniform; ++i)
      uniform = eps[i] == 1.0 && epsOld[i] == 1.0 && K[i] == 0.0;
    if (decomposition_->distributed()) uniform = maxAcrossRanks(uniform ? 0.0 : 1.0) == 0.0;
  }
  uniformCoupling_ = uniform;
  if (steps_ == 0) epsOlder_ = coupling_.voidFractionOld;
  stats_ = StepStatistics{};
  rhoOld_.data() = rhoCell_.data();
  transportPhases(dt);  // alpha^n -> alpha^{n+1} with the last projection's fluxes
  updateMixture();      // rho^{n+1}, mu^{n+1}
  predictMomentumVof(dt);
  if (predictorHook_) predictorHook_(u_, dt, 1.0);
  balanceOutflow(dt);
  {
    ScopedPhase pt(timers_, Phase::PressureSolve);
    project(dt, 1.0);
  }
  // eps^{n-1}, eps^n, eps^{n+1} all 1: eps* is eps^{n+1} to the solver's tolerance already
  // (eps^{n-1} read from its field, not from a flag: a run restarted from a checkpoint decides as
  // the uninterrupted one did)
  bool olderOnes = uniform;  // (only asked where eps^n and eps^{n+1} are uniform; uniform is collective)
  if (olderOnes) {
    for (int k = 0; k < grid_.cells[2]; ++k)
      for (int j = 0; j < grid_.cells[1]; ++j)
        for (int i = 0; i < grid_.cells[0]; ++i) olderOnes = olderOnes && epsOlder_(i, j, k) == 1.0;
    if (decomposition_->distributed()) olderOnes = maxAcrossRanks(olderOnes ? 0.0 : 1.0) == 0.0;
  }
  if (!olderOnes) transportPhasesToProjection(dt);
  updateMixture();  // (rho, mu of the corrected fractions; p = p* + rho g.x with the new p*)
  epsOlder_ = coupling_.voidFractionOld;
  epsStep_ = coupling_.voidFraction;
  epsStepOnes_ = uniform;
  finishStep(dt);
}

}  // namespace gf::fluid
