#pragma once
// Volume-averaged incompressible Navier-Stokes on a staggered (MAC) Cartesian grid.
//
//   d(eps)/dt + div(eps u) = 0
//   rho [d(eps u)/dt + div(eps u u)] = -a grad p + div(eps mu grad u) + eps rho g + F - K (u - u_p)
//   a = eps (model A) or 1 (model B)                  (seed 000 eq. 5.7; seed 001 lines 31-70)
//
// eps = 1, F = K = 0 is exactly the incompressible Navier-Stokes equations. Time stepping: BDF2
// (variable step) with extrapolated convection (Karniadakis et al. 1991), implicit viscous and
// drag terms, incremental pressure-correction projection with an eps-weighted Poisson equation
// solved by multigrid-preconditioned CG. See docs/fluid.md.
//
// Contract used by the app and the coupling:
//   Solver(root, domain, gravity)  reads section 'fluid'
//   couplingFields()               eps, eps_old, force density, K, mean particle velocity
//   step(dt), stableTimeStep(), checkHealth(step, time), save/load, timers()
//   cellVelocity(out), pressureGradient(out), pressure(), cellFields() for output
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/coupling_fields.hpp"
#include "core/domain.hpp"
#include "core/grid.hpp"
#include "core/params.hpp"
#include "core/serialize.hpp"
#include "core/timers.hpp"
#include "fluid/boundary.hpp"
#include "fluid/gathered_pressure.hpp"
#include "fluid/hypre_pressure.hpp"
#include "fluid/multigrid.hpp"
#include "fluid/team_tuner.hpp"
#include "parallel/decomposition.hpp"
#include "vof/vof.hpp"

namespace gf::fluid {

struct PlaneSlab;         // fluid/loops.hpp
struct MomentumRhsPoint;  // fluid/momentum_rhs.hpp

enum class MomentumModel { A, B };
enum class ConvectionScheme { Central, VanLeer };
enum class DrivingMode { None, PressureGradient, FlowRate };
/// Whether a derived cell field (cellVelocity, pressureGradient) gets its ghost layers filled:
/// Filled (boundary values), Left (untouched; on a decomposed grid those across the cuts are
/// exchanged with the neighbours), Unexchanged (untouched, also across the cuts: the caller
/// exchanges several fields at once).
enum class CellGhosts { Filled, Left, Unexchanged };

struct NamedCellField {
  std::string name;
  std::string unit;
  Field field;  // cell-centred
};

struct StepStatistics {
  int pressureIterations = 0;
  double pressureResidual = 0.0;  // relative
  int momentumIterations = 0;     // summed over components
  // (max |div(eps u) + d eps/dt| after the projection: Solver::maxDivergence(), on demand -- a
  // full pass over the cells, not made every step)
  /// correctors > 1: relative momentum residual ||b - A u|| / ||b|| of the velocity and pressure
  /// entering the last corrector (the splitting error the correctors remove); 0 otherwise.
  double momentumResidual = 0.0;
};

class Solver {
 public:
  /// decomposition: the ranks' layout when the grid is split among MPI ranks (this rank's grid is
  /// its box: Decomposition::cellOffset/cellCount of fluid.cells). One rank (the default): the
  /// whole grid, the single-process solver. A decomposition of several ranks built without the
  /// grid's cells is rebuilt here with them (same layout); one built with other cells is refused.
  /// On several ranks the pressure goes through the multigrid on rank 0 for a grid of at most
  /// fluid.pressure.gather_cells cells (fluid/gathered_pressure.hpp), through hypre otherwise or
  /// when the case asks for it (fluid.pressure.solver: hypre); ghost layers are exchanged with the neighbour ranks
  /// (parallel/halo.hpp) and the solvers' reductions are allreduces (parallel/reductions.hpp).
  Solver(Params& root, const Domain& domain, const Vec3& gravity,
         const parallel::Decomposition& decomposition = parallel::Decomposition());

  /// This rank's grid (the whole grid on one rank): origin, spacing, cells of its box.
  const CartesianGrid& grid() const { return grid_; }
  /// The ranks' layout this solver works on (one rank: the whole grid).
  const parallel::Decomposition& decomposition() const { return *decomposition_; }
  /// The whole domain's grid (one rank: grid()); this rank's box starts at cell cellOffset() of it.
  const CartesianGrid& globalGrid() const { return globalGrid_; }
  std::array<int, 3> cellOffset() const {
    return decomposition_->distributed() ? decomposition_->cellOffset() : std::array<int, 3>{0, 0, 0};
  }
  CouplingFields& couplingFields() { return coupling_; }
  const CouplingFields& couplingFields() const { return coupling_; }

  void step(double dt);
  /// Largest dt with CFL <= fluid.cfl for the current velocity (max double when at rest).
  double stableTimeStep() const;
  /// Cell-centred velocity (mean of the two face velocities). CellGhosts::Filled: zero-gradient
  /// ghosts as well; CellGhosts::Left: interior cells only, the ghosts keep what they held (for
  /// readers of the interior only, e.g. the coupling's FluidView: six ghost fills per fluid step of
  /// a 2 x 30 x 90 bed cost as much as the values themselves). On a decomposed grid both fill the
  /// ghosts across the cuts from the neighbour ranks (collective: every rank calls these).
  void cellVelocity(Field out[3], CellGhosts ghosts = CellGhosts::Filled) const;
  /// Cell-centred grad p, including the mean driving gradient (-drivingPressureGradient()) along
  /// the driving axis; ghosts as cellVelocity.
  void pressureGradient(Field out[3], CellGhosts ghosts = CellGhosts::Filled) const;
  /// The pressure p (with a VOF mixture, fluid.vof: p = p* + rho_f g.x from the solved modified
  /// pressure p*, seed 002 line 330).
  const Field& pressure() const { return vof_ ? pTotal_ : p_; }
  void checkHealth(long long step, double time) const;
  void save(BinaryWriter& out) const;
  void load(BinaryReader& in);
  PhaseTimers& timers() { return timers_; }

  // Read access for output, monitors and tests.
  const Field& velocity(int component) const { return u_[component]; }
  const Field& scalar() const { return scalar_; }
  bool hasScalar() const { return scalarEnabled_; }
  std::vector<NamedCellField> cellFields() const;
  double density() const { return rho_; }
  double viscosity() const { return mu_; }
  MomentumModel model() const { return model_; }
  const StepStatistics& lastStep() const { return stats_; }
  /// Mean driving pressure gradient -dp/dx along the driving axis (imposed or found by flow-rate control), Pa/m.
  double drivingPressureGradient() const { return drive_; }
  int drivingAxis() const { return driveAxis_; }
  bool blocked(int i, int j, int k) const { return blocked_[p_.index(i, j, k)] != 0; }
  bool twoD() const { return twoD_; }
  const Boundaries& boundaries() const { return bc_; }
  double time() const { return time_; }
  long long stepsDone() const { return steps_; }
  /// max over cells of |div(eps u) + (eps - eps_old)/dt| for the current velocity, the last dt and
  /// the eps pair that step used (a coupler may have moved the coupling fields on since).
  double maxDivergence() const;

  // Several immiscible fluids by volume of fluid (fluid.vof; docs/vof.md, fluid/vof_step.cpp).
  /// fluid.vof is given: the phase fractions are transported and the mixture sets rho and mu.
  bool vofEnabled() const { return vof_; }
  int phaseCount() const { return static_cast<int>(phases_.size()); }
  const std::string& phaseName(int i) const { return phases_[static_cast<std::size_t>(i)].name; }
  double phaseDensity(int i) const { return phases_[static_cast<std::size_t>(i)].density; }
  double phaseViscosity(int i) const { return phases_[static_cast<std::size_t>(i)].viscosity; }
  /// Index of the phase called `name`, -1 if none.
  int phaseIndex(const std::string& name) const;
  /// Fraction alpha_i of phase i (cell field of this rank's box, ghosts filled).
  const Field& phaseFraction(int i) const { return alpha_[static_cast<std::size_t>(i)]; }
  /// Mixture density and viscosity of the cells (seed 002 eqs. 3-4), of the fractions at the end
  /// of the last step (ghosts filled).
  const Field& mixtureDensity() const { return rhoCell_; }
  const Field& mixtureViscosity() const { return muCell_; }
  /// Volume of phase i that has left through the open sides since the start (m^3, all ranks).
  double phaseOutflowVolume(int i) const { return phaseOutflow_[static_cast<std::size_t>(i)]; }
  /// Its rate over the last step (m^3/s).
  double phaseOutflowRate(int i) const { return phaseOutflowRate_[static_cast<std::size_t>(i)]; }
  /// The void fraction the phase fractions hold their contents with: the eps^{n+1} of the last
  /// step's continuity equation (a coupler may have moved the coupling fields on since), or the
  /// coupling's before the first step. Phase masses are sum rho_i eps alpha_i V with it.
  const Field& phaseVoidFraction() const { return epsStepKept_ ? epsStep_ : coupling_.voidFraction; }
  /// Substeps of the phase transport in the last step.
  int vofSubsteps() const { return vofSubsteps_; }
  /// Fill the phase fractions from a function of position (the phase of each cell centre), and
  /// the mixture fields from them (tests; the case file's fluid.vof.regions does the same).
  void setPhases(const std::function<int(const Vec3&)>& phaseAt);

  /// Direct-forcing hook (resolved CFD-DEM, src/resolved; seed 000 lines 471-510): called by step()
  /// once, after the momentum predictor and before the pressure projection, with the predicted face
  /// velocities of this rank's box (u-hat, which the hook may overwrite with u-tilde), the step and
  /// the BDF coefficient gamma0 of the time derivative (a change du of a face velocity is the body
  /// force rho gamma0 du / dt). The projection then makes the forced field divergence-free. With
  /// fluid.pressure.correctors > 1 the later correctors do not call it again. Empty: no forcing.
  using PredictorHook = std::function<void(Field (&u)[3], double dt, double gamma0)>;
  void setPredictorHook(PredictorHook hook) { predictorHook_ = std::move(hook); }

  // Initial conditions (also used by tests): set u^n (= u^{n-1}), p, scalar from functions of position.
  void setVelocity(const std::function<Vec3(const Vec3&)>& f);
  void setPressure(const std::function<double(const Vec3&)>& f);
  void setScalar(const std::function<double(const Vec3&)>& f);

 private:
  void readParams(Params& fluid, const Domain& domain);
  /// checkHealth's tests without the report: true where every value is finite and the CFL number
  /// within cfl_limit (solver.cpp).
  bool healthyFast() const;
  void markBlocked(Params& fluid);
  void buildUnknownMasks();
  void fillAllGhosts();
  // momentum.cpp
  /// slab: only the grid lines of that team member (the cell divergence computed before); null:
  /// all lines, cell divergence included, threaded loop by loop.
  /// rho, mu >= 0: the density and viscosity the kernels take instead of the fluid's (the VOF
  /// step's convection per unit density, without the eps-varying viscous rest).
  void computeConvection(Field out[3], const PlaneSlab* slab = nullptr, double rho = -1.0, double mu = -1.0);
  void computeCellDivergence(const PlaneSlab* slab);
  /// A team member's share of computeConvection + assembleMomentum (all components) in one pass,
  /// with |b|^2 per grid line into partial[c] (momentum_team.cpp).
  void convectAndAssemble(const PlaneSlab& slab, double dt, double g1, double g2, double e1, double e2,
                          double* const partial[3]);
  MomentumRhsPoint momentumRhsPoint(int c, double dt, double g1, double g2, double e1, double e2) const;
  // momentum_team.cpp
  /// Convection, right-hand sides and Jacobi momentum solves of all components in one parallel
  /// region (threads split the z planes; few barriers) where eps varies and Jacobi applies;
  /// false (nothing done) otherwise. Results as computeConvection + assembleMomentum + solveHelmholtz.
  bool predictMomentumTeam(double dt, double gamma0, double gamma1, double gamma2, double ext1, double ext2);
  /// Right-hand side of component c on grid lines [lineBegin, lineEnd) (lineEnd < 0: all, threaded).
  void assembleMomentum(int c, double dt, double gamma0, double gamma1, double gamma2, double ext1, double ext2,
                        std::int64_t lineBegin = 0, std::int64_t lineEnd = -1);
  /// predictor: start from 2 u^n - u^{n-1} and move u^n to uOld_; else (corrector) start from u.
  int solveHelmholtz(int c, double dt, double gamma0, bool predictor = true);
  void applyHelmholtz(int c, const Field& x, std::vector<double>& y, double dt, double gamma0) const;
  /// Calls body(face, cell) for every face of boundary side s (0 = min, 1 = max) normal to axis a:
  /// face = (i, j, k) of the normal-velocity face, cell = the interior cell next to it.
  template <class Body>
  void forEachBoundaryFace(int a, int s, Body&& body) const {
    const int n = grid_.cells[a];
    const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
    for (int q = 0; q < grid_.cells[b2]; ++q)
      for (int p = 0; p < grid_.cells[b1]; ++p) {
        int face[3];
        face[a] = s == 0 ? 0 : n;
        face[b1] = p;
        face[b2] = q;
        int cell[3] = {face[0], face[1], face[2]};
        if (s == 1) cell[a] = n - 1;
        body(static_cast<const int*>(face), static_cast<const int*>(cell));
      }
  }
  // vof_step.cpp
  void readVof(Params& fluid);
  /// step() with a VOF mixture: explicit predictor with rho_f, mu_f and the buoyancy face force,
  /// projection with 1/rho_f, then the phase transport with the projected fluxes.
  void stepVof(double dt);
  void predictMomentumVof(double dt);
  void transportPhases(double dt);
  void transportPhasesToProjection(double dt);
  void updateMixture();
  vof::Sides vofSides() const;
  /// The phase fractions' ghost fill for these sides (the neighbour ranks' cells on a decomposed grid).
  vof::GhostFill vofGhostFill(const vof::Sides& sides) const;
  /// outflow[i] += h x phase i's outflow rate through the open sides of the domain (m^3/s; inflow
  /// negative) of the transport's last substep.
  void addBoundaryOutflow(std::vector<double>& outflow, double h, const vof::Sides& sides) const;
  // projection.cpp
  void balanceOutflow(double dt);
  void project(double dt, double gamma0);
  void controlFlowRate(double dt, double gamma0);
  double correctMomentum(double dt, double gamma0);
  // scalar.cpp
  void advanceScalar(double dt);
  /// The end of a step (single fluid or VOF): the step's bookkeeping (eps kept, step sizes, time,
  /// count) and the passive scalar.
  void finishStep(double dt);

  CartesianGrid grid_;
  std::shared_ptr<const parallel::Decomposition> decomposition_;  // (shared with bc_: survives moves)
  CartesianGrid globalGrid_;
  Domain domain_;
  Vec3 gravity_;
  Boundaries bc_;
  bool twoD_ = false;
  double rho_ = 1.0, mu_ = 1e-3;
  MomentumModel model_ = MomentumModel::A;
  ConvectionScheme scheme_ = ConvectionScheme::VanLeer;
  double cfl_ = 0.5, cflLimit_ = 1.0;
  double momentumTolerance_ = 1e-8;
  int momentumMaxIterations_ = 200;
  double pressureTolerance_ = 1e-8;
  int pressureMaxIterations_ = 200;
  int correctors_ = 1;  // pressure projections per step (PISO-style correctors beyond the first)
  DrivingMode driveMode_ = DrivingMode::None;
  int driveAxis_ = 0;
  double drive_ = 0.0;         // -dp/dx applied as body force, Pa/m
  double bulkVelocity_ = 0.0;  // flow-rate target (mean superficial velocity), m/s
  bool scalarEnabled_ = false;
  double scalarDiffusivity_ = 0.0, scalarSource_ = 0.0;

  CouplingFields coupling_;
  Field u_[3], uOld_[3];        // u^n (after step: u^{n+1}) and u^{n-1}
  Field guessError_[3];         // predicted velocity minus its initial guess in the last step (momentum.cpp)
  Field conv_[3], convOld_[3];  // convective term N^n, N^{n-1}
  Field rhs_[3];
  Field p_, phi_, epsOlder_, scalar_;
  /// eps of the last step (the eps^{n+1} its continuity equation used; with epsOlder_, its eps^n):
  /// maxDivergence() after the step, when a coupler has already moved the coupling fields on.
  Field epsStep_;
  bool epsStepOnes_ = true;   // epsStep_ is 1 everywhere (ghosts included)
  bool epsStepKept_ = false;  // a step has run since construction or restart (else: coupling fields)
  Field cellDivergence_;  // div u per cell for the eps-varying viscous stress (momentum.cpp)
  std::vector<std::uint8_t> blocked_;     // per cell-field point
  std::vector<std::uint8_t> unknown_[3];  // per face point: solved by the momentum equation
  std::vector<std::int64_t> unknownList_[3];
  bool anyUnknowns_[3] = {false, false, false};  // some rank has unknowns of the component
  std::vector<std::int64_t> unknownLineStart_[3];  // first unknownList_ entry of each grid line (+ end)
  /// Jacobi row of one momentum unknown for the current step (momentum_team.cpp): the diagonal
  /// with and without the no-slip closure terms and the control-volume face eps, in unknownList_ order.
  struct JacobiRow {
    double diag, invD, ep[3], em[3];
  };
  std::vector<JacobiRow> jacobiRows_[3];
  std::vector<double> krylov_[7];  // r, rhat, p, v, s, t, 1/diag
  Field precY_[3], precZ_[3];
  std::vector<double> linePartial_;  // per-line partial sums (deterministic reductions)
  /// ||b||^2 of component c, computed by assembleMomentum's eps = 1 path along with b, for the
  /// predictor's solveHelmholtz (kept: valid for that solve only).
  double rhsNorm2_[3] = {0.0, 0.0, 0.0};
  bool rhsNorm2Kept_[3] = {false, false, false};
  TeamTuner momentumTeam_;    // one thread or a team for predictMomentumTeam (speed only)
  TeamTuner projectTeam_[2];  // project(): coefficients + right-hand side, correction + p update
  mutable TeamTuner cellVelocityTeam_, pressureGradientTeam_;  // cellVelocity(), pressureGradient()
  TeamTuner ghostTeam_;                                         // fillAllGhosts()
  /// body(slab) on a plane team (teamSize(), members own >= 2 planes, z not periodic) or
  /// body(nullptr) once (solver.cpp).
  template <class Body>
  void forCellPlanes(TeamTuner& tuner, Body&& body) const;
  /// line(l) on the cell lines of the slab (null: all), then (CellGhosts::Filled) the zero-gradient
  /// ghosts of out there.
  template <class Line>
  void cellLinesAndGhosts(const PlaneSlab* slab, Field& out, Line&& line, CellGhosts ghosts) const;
  /// Largest useful thread team for the plane-split phases of a small 3D grid (1: loop by loop).
  int teamSize() const;
  std::vector<double> epsMemberRange_;      // momentum_team.cpp: min and max of eps per team member
  std::vector<double> teamPartial_[3][3];  // momentum_team.cpp: per component, ||b||^2 and two sweep parities
  MultigridPoisson poisson_;
  /// fluid.pressure.solver: hypre: the pressure goes through HyprePressure instead of poisson_
  /// (created at the first projection).
  bool hyprePressure_ = false;
  std::shared_ptr<HyprePressure> hypre_;
  /// Several ranks with fluid.pressure.solver: multigrid on a grid small enough to gather: the
  /// pressure goes through GatheredPressure (created at the first projection).
  bool gatheredPressure_ = false;
  std::shared_ptr<GatheredPressure> gathered_;
  double poissonKey_ = -1.0;  // rho gamma0 / dt of the current multigrid setup (-1: rebuild)
  bool uniformCoupling_ = true;
  bool epsOlderOnes_ = true;  // epsOlder_ is 1 everywhere (ghosts included)
  std::vector<double> poissonRhs_, poissonX_, firstIncrement_;
  std::array<std::vector<double>, 3> poissonT_;          // face transmissibilities handed to poisson_
  std::vector<std::uint8_t> pressureFaces_[3];           // projection.cpp: 1 coefficient face, 2 corrected face
  std::vector<double> correctionCoeff_[3];               // a / (rho gamma0 eps_f/dt + K_f) per face (this step)

  /// The velocity and pressure ghosts are those of project()'s full fill and the interior values
  /// unchanged since: the next step refills only what depends on time and eps (fillAllGhosts).
  bool ghostsFresh_ = false;
  double time_ = 0.0, dtPrev_ = 0.0, lastDt_ = 0.0;
  long long steps_ = 0;
  mutable long long healthCheckedAt_ = -1;  // steps_ at the last complete health scan
  StepStatistics stats_;
  PhaseTimers timers_;
  PredictorHook predictorHook_;  // setPredictorHook

  // VOF (fluid.vof; fluid/vof_step.cpp). Empty / false: the single-fluid solver.
  struct VofPhase {
    std::string name;
    double density = 1000.0, viscosity = 1e-3;
  };
  bool vof_ = false;
  std::vector<VofPhase> phases_;
  std::vector<Field> alpha_;          // phase fractions (cell fields)
  Field rhoCell_, muCell_, pTotal_;   // mixture rho, mu; p = p* + rho g.x (p_ holds p*)
  Field vofEps_, vofFlux_[3];         // eps at the start of the transport, eps_f u_f per axis
  Field massFlux_[3];                 // sum_i rho_i F^L_i (upwind) of the step's transport per axis (face fields)
  Field rhoOld_;                      // mixture density before the step's transport
  vof::PhaseTransport transport_;
  vof::TransportSettings vofSettings_;
  double vofCourant_ = 0.5;
  int vofInflowPhase_ = 0;
  std::array<int, 6> vofSidePhase_{};  // per side: the phase entering there (boundaries.<side>.phase)
  int vofSubsteps_ = 0;
  std::vector<double> phaseOutflow_, phaseOutflowRate_;
};

}  // namespace gf::fluid
